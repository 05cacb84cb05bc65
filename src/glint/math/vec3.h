#pragma once
/// Three-component vectors for points, directions, normals and RGB colours.
///
/// Two precisions, each with one job (docs/design.md explains the split):
///  - `Vec3` (double): scene description, camera, shading, colours, secondary-ray set-up;
///  - `Vec3f` (float): compact geometry storage, bounding boxes and traversal, the hot path.

#include <algorithm>
#include <cmath>
#include <iosfwd>

namespace glint {

template <typename T>
struct Vec3T {
    T x = 0, y = 0, z = 0;

    constexpr Vec3T() = default;
    constexpr Vec3T(T x_, T y_, T z_) : x(x_), y(y_), z(z_) {}
    constexpr explicit Vec3T(T v) : x(v), y(v), z(v) {}
    /// Conversion between precisions is always explicit.
    template <typename U>
    constexpr explicit Vec3T(const Vec3T<U>& v)
        : x(static_cast<T>(v.x)), y(static_cast<T>(v.y)), z(static_cast<T>(v.z)) {}

    constexpr T operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
    constexpr T& operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }

    constexpr Vec3T operator-() const { return {-x, -y, -z}; }
    constexpr Vec3T& operator+=(const Vec3T& b) {
        x += b.x;
        y += b.y;
        z += b.z;
        return *this;
    }
    constexpr Vec3T& operator-=(const Vec3T& b) {
        x -= b.x;
        y -= b.y;
        z -= b.z;
        return *this;
    }
    constexpr Vec3T& operator*=(T s) {
        x *= s;
        y *= s;
        z *= s;
        return *this;
    }
    constexpr bool operator==(const Vec3T&) const = default;
};

using Vec3 = Vec3T<double>;
using Vec3f = Vec3T<float>;
/// "(x, y, z)", at the stream's precision: for messages, debug output and failing tests.
std::ostream& operator<<(std::ostream& out, const Vec3& v);
std::ostream& operator<<(std::ostream& out, const Vec3f& v);

template <typename T>
constexpr Vec3T<T> operator+(const Vec3T<T>& a, const Vec3T<T>& b) {
    return {a.x + b.x, a.y + b.y, a.z + b.z};
}
template <typename T>
constexpr Vec3T<T> operator-(const Vec3T<T>& a, const Vec3T<T>& b) {
    return {a.x - b.x, a.y - b.y, a.z - b.z};
}
/// Component-wise product (colours).
template <typename T>
constexpr Vec3T<T> operator*(const Vec3T<T>& a, const Vec3T<T>& b) {
    return {a.x * b.x, a.y * b.y, a.z * b.z};
}
template <typename T>
constexpr Vec3T<T> operator/(const Vec3T<T>& a, const Vec3T<T>& b) {
    return {a.x / b.x, a.y / b.y, a.z / b.z};
}
template <typename T>
constexpr Vec3T<T> operator*(const Vec3T<T>& a, T s) {
    return {a.x * s, a.y * s, a.z * s};
}
template <typename T>
constexpr Vec3T<T> operator*(T s, const Vec3T<T>& a) {
    return {a.x * s, a.y * s, a.z * s};
}
template <typename T>
constexpr Vec3T<T> operator/(const Vec3T<T>& a, T s) {
    return {a.x / s, a.y / s, a.z / s};
}

template <typename T>
constexpr T dot(const Vec3T<T>& a, const Vec3T<T>& b) {
    return a.x * b.x + a.y * b.y + a.z * b.z;
}
template <typename T>
constexpr Vec3T<T> cross(const Vec3T<T>& a, const Vec3T<T>& b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
template <typename T>
inline T length(const Vec3T<T>& a) {
    return std::sqrt(dot(a, a));
}
template <typename T>
inline Vec3T<T> normalize(const Vec3T<T>& a) {
    return a / length(a);
}
template <typename T>
constexpr Vec3T<T> min(const Vec3T<T>& a, const Vec3T<T>& b) {
    return {std::min(a.x, b.x), std::min(a.y, b.y), std::min(a.z, b.z)};
}
template <typename T>
constexpr Vec3T<T> max(const Vec3T<T>& a, const Vec3T<T>& b) {
    return {std::max(a.x, b.x), std::max(a.y, b.y), std::max(a.z, b.z)};
}
template <typename T>
inline Vec3T<T> abs(const Vec3T<T>& a) {
    return {std::abs(a.x), std::abs(a.y), std::abs(a.z)};
}
/// Luminance Y of linear RGB with the Rec. 709 (sRGB) primaries.
template <typename T>
constexpr T luminance(const Vec3T<T>& c) {
    return T(0.2126) * c.x + T(0.7152) * c.y + T(0.0722) * c.z;
}

template <typename T>
constexpr T maxComponent(const Vec3T<T>& a) {
    return std::max(a.x, std::max(a.y, a.z));
}
template <typename T>
inline bool isFinite(const Vec3T<T>& a) {
    return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z);
}
/// Mirror reflection of the incident direction `d` about the unit normal `n`.
template <typename T>
constexpr Vec3T<T> reflect(const Vec3T<T>& d, const Vec3T<T>& n) {
    return d - n * (2 * dot(d, n));
}

}  // namespace glint
