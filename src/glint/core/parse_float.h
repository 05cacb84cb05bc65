#pragma once
/// Reading a float or double from text as std::from_chars does (its general format: an optional
/// '-', decimal digits with an optional point and exponent, or inf, infinity, nan; no leading
/// '+' or blank; correctly rounded), for the standard libraries that lack the floating-point
/// std::from_chars: parse_float.cpp natively, parse_float_web.cpp in WebAssembly (Emscripten's
/// libc++ 13 has no floating-point from_chars).

#include <charconv>

namespace glint {

/// std::from_chars(first, last, value) for double: on success, `value` and the end of the
/// number; std::errc::invalid_argument with `first` when there is none; result_out_of_range
/// (value unchanged) when the number lies beyond the type's range.
std::from_chars_result parseFloat(const char* first, const char* last, double& value);
/// The same for float: rounded once, from the text.
std::from_chars_result parseFloat(const char* first, const char* last, float& value);

}  // namespace glint
