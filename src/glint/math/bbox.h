#pragma once
/// Axis-aligned bounding boxes, in float: they exist for traversal.

#include <cmath>
#include <iosfwd>
#include <limits>

#include "glint/math/vec3.h"

namespace glint {

struct Bounds3f {
    Vec3f lo{std::numeric_limits<float>::infinity()};
    Vec3f hi{-std::numeric_limits<float>::infinity()};

    /// The smallest float box containing the double-precision box [lo, hi] (rounded outwards).
    static Bounds3f enclosing(const Vec3& lo, const Vec3& hi);

    constexpr bool empty() const { return lo.x > hi.x || lo.y > hi.y || lo.z > hi.z; }
    constexpr void extend(const Vec3f& p) {
        lo = min(lo, p);
        hi = max(hi, p);
    }
    constexpr void extend(const Bounds3f& b) {
        lo = min(lo, b.lo);
        hi = max(hi, b.hi);
    }
    constexpr Vec3f diagonal() const { return hi - lo; }
    constexpr Vec3f centroid() const { return (lo + hi) * 0.5f; }
    /// Surface area; 0 for an empty box.
    constexpr float area() const {
        if (empty()) return 0;
        Vec3f d = diagonal();
        return 2 * (d.x * d.y + d.y * d.z + d.z * d.x);
    }
    /// Axis (0, 1, 2) of the largest extent.
    constexpr int longestAxis() const {
        Vec3f d = diagonal();
        return d.x >= d.y && d.x >= d.z ? 0 : (d.y >= d.z ? 1 : 2);
    }
};
/// "[(lo) .. (hi)]", or "[empty]".
std::ostream& operator<<(std::ostream& out, const Bounds3f& b);

inline Bounds3f Bounds3f::enclosing(const Vec3& lo, const Vec3& hi) {
    constexpr float inf = std::numeric_limits<float>::infinity();
    Bounds3f b;
    for (int a = 0; a < 3; ++a) {
        float l = static_cast<float>(lo[a]), h = static_cast<float>(hi[a]);
        if (static_cast<double>(l) > lo[a]) l = std::nextafter(l, -inf);
        if (static_cast<double>(h) < hi[a]) h = std::nextafter(h, inf);
        b.lo[a] = l;
        b.hi[a] = h;
    }
    return b;
}

}  // namespace glint
