#pragma once
/// Maps from uniform random numbers in [0, 1) to points and directions.

#include <cmath>
#include <numbers>
#include <utility>

#include "glint/math/vec3.h"

namespace glint {

/// A point uniformly distributed on the unit disk, by Shirley and Chiu's concentric map
/// ("A Low Distortion Map Between Disk and Square", 1997): strata of the square stay compact.
inline std::pair<double, double> sampleUniformDisk(double u, double v) {
    double a = 2 * u - 1, b = 2 * v - 1;
    if (a == 0 && b == 0) return {0, 0};
    constexpr double kQuarterPi = std::numbers::pi / 4;
    double r, phi;
    if (std::abs(a) > std::abs(b)) {
        r = a;
        phi = kQuarterPi * (b / a);
    } else {
        r = b;
        phi = 2 * kQuarterPi - kQuarterPi * (a / b);
    }
    return {r * std::cos(phi), r * std::sin(phi)};
}

/// An orthonormal basis (t, b, n) around the unit vector n (Duff et al., "Building an
/// Orthonormal Basis, Revisited", JCGT 2017).
struct Frame {
    Vec3 t, b, n;

    explicit Frame(const Vec3& normal) : n(normal) {
        double sign = std::copysign(1.0, n.z);
        double a = -1 / (sign + n.z);
        double c = n.x * n.y * a;
        t = Vec3(1 + sign * n.x * n.x * a, sign * c, -sign * n.x);
        b = Vec3(c, sign + n.y * n.y * a, -n.y);
    }
    Vec3 toLocal(const Vec3& v) const { return {dot(v, t), dot(v, b), dot(v, n)}; }
    Vec3 toWorld(const Vec3& v) const { return t * v.x + b * v.y + n * v.z; }
};

}  // namespace glint
