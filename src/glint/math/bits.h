#pragma once
/// Reinterpreting the bits of a value as another type of the same size.

namespace glint {

/// std::bit_cast's meaning, through the builtin both GCC and Clang have (Emscripten's libc++ 13,
/// the web build's, has no std::bit_cast yet).
template <typename To, typename From>
constexpr To bitCast(const From& from) noexcept {
    static_assert(sizeof(To) == sizeof(From), "bitCast between types of different sizes");
    return __builtin_bit_cast(To, from);
}

}  // namespace glint
