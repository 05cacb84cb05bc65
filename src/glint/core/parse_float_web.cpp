// parseFloat in WebAssembly (core/parse_float.h): Emscripten's libc++ 13 has no floating-point
// std::from_chars, so the number is read by strtod or strtof (musl's, correctly rounded, in the
// "C" locale the module never changes), from a NUL-terminated copy of the longest run of
// characters a number could use, after refusing what std::from_chars refuses and strtod would
// take (a leading blank or '+', a hexadecimal number).

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <string>

#include "glint/core/parse_float.h"

namespace glint {
namespace {

bool numberChar(char c) {
    return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '.' ||
           c == '+' || c == '-' || c == '(' || c == ')' || c == '_';
}

template <typename T, typename Read>
std::from_chars_result parse(const char* first, const char* last, T& value, Read read) {
    const char* stop = first;
    while (stop != last && numberChar(*stop)) ++stop;
    const char* digits = first + (stop != first && *first == '-');
    if (stop == first || *first == '+' || digits == stop || *digits == '+' || *digits == '-')
        return {first, std::errc::invalid_argument};
    // "0x1p3": std::from_chars reads the "0" alone.
    if (stop - digits > 1 && digits[0] == '0' && (digits[1] == 'x' || digits[1] == 'X'))
        stop = digits + 1;
    char small[64];
    std::string large;
    const size_t n = static_cast<size_t>(stop - first);
    char* text = small;
    if (n < sizeof small) {
        std::memcpy(small, first, n);
        small[n] = '\0';
    } else {
        large.assign(first, n);
        text = large.data();
    }
    char* end = nullptr;
    errno = 0;
    T v = read(text, &end);
    if (end == text) return {first, std::errc::invalid_argument};
    const char* ptr = first + (end - text);
    // Beyond the range: infinite, or zero for a number that is not (a denormal result is in
    // range, as std::from_chars has it, though strtod reports ERANGE for it too).
    if (errno == ERANGE && (v == 0 || v - v != 0)) return {ptr, std::errc::result_out_of_range};
    value = v;
    return {ptr, std::errc()};
}

}  // namespace

std::from_chars_result parseFloat(const char* first, const char* last, double& value) {
    return parse(first, last, value, [](const char* s, char** end) { return std::strtod(s, end); });
}

std::from_chars_result parseFloat(const char* first, const char* last, float& value) {
    return parse(first, last, value, [](const char* s, char** end) { return std::strtof(s, end); });
}

}  // namespace glint
