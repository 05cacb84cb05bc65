#pragma once
/// Maps from uniform random numbers in [0, 1) to points and directions.

#include <algorithm>
#include <cmath>
#include <iosfwd>
#include <numbers>
#include <utility>

#include "glint/math/vec3.h"

namespace glint {

/// A point of the unit square [0, 1)^2: two uniform random numbers, the input of the 2D maps
/// below and of the samplers of lights and BSDFs.
struct Point2 {
    double x = 0, y = 0;
};
/// "(x, y)".
std::ostream& operator<<(std::ostream& out, const Point2& p);

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

/// A unit direction about +z with density cos(theta) / pi over the upper hemisphere, by
/// Malley's method: the concentric disk point lifted onto the hemisphere. z may be 0 (density
/// 0) at the disk's rim.
inline Vec3 sampleCosineHemisphere(Point2 u) {
    auto [x, y] = sampleUniformDisk(u.x, u.y);
    return {x, y, std::sqrt(std::max(0.0, 1 - x * x - y * y))};
}

/// A unit direction uniformly distributed over the hemisphere z > 0 (density 1 / (2 pi)).
inline Vec3 sampleUniformHemisphere(Point2 u) {
    double z = u.x, r = std::sqrt(std::max(0.0, 1 - z * z));
    double phi = 2 * std::numbers::pi * u.y;
    return {r * std::cos(phi), r * std::sin(phi), z};
}

/// A unit direction uniformly distributed over the sphere (density 1 / (4 pi)).
inline Vec3 sampleUniformSphere(Point2 u) {
    double z = 1 - 2 * u.x;
    double r = std::sqrt(std::max(0.0, 1 - z * z));
    double phi = 2 * std::numbers::pi * u.y;
    return {r * std::cos(phi), r * std::sin(phi), z};
}

/// A point uniformly distributed over the triangle with corners a, b, c, as barycentric
/// weights (b0, b1) of a and b (Heitz's low-distortion map, "A Low-Distortion Map Between
/// Triangle and Square", 2019).
inline std::pair<double, double> sampleUniformTriangle(Point2 u) {
    double b0, b1;
    if (u.x < u.y) {
        b0 = u.x / 2;
        b1 = u.y - b0;
    } else {
        b1 = u.y / 2;
        b0 = u.x - b1;
    }
    return {b0, b1};
}

/// An orthonormal basis (t, b, n) around the unit vector n (Duff et al., "Building an
/// Orthonormal Basis, Revisited", JCGT 2017).
/// Veach's power heuristic (exponent 2): the weight of a sample drawn with density `a` by one
/// strategy when another would have drawn it with density `b`.
inline double powerHeuristic(double a, double b) {
    double a2 = a * a, b2 = b * b;
    return a2 > 0 ? a2 / (a2 + b2) : 0;
}

struct Frame {
    Vec3 t, b, n;

    explicit Frame(const Vec3& normal) : n(normal) {
        double sign = std::copysign(1.0, n.z);
        double a = -1 / (sign + n.z);
        double c = n.x * n.y * a;
        t = Vec3(1 + sign * n.x * n.x * a, sign * c, -sign * n.x);
        b = Vec3(c, sign + n.y * n.y * a, -n.y);
    }
    /// A frame about `normal` whose x axis is `tangent` made perpendicular to it (the
    /// frame above where `tangent` is along the normal).
    Frame(const Vec3& normal, const Vec3& tangent) : Frame(normal) {
        const Vec3 across = tangent - n * dot(n, tangent);
        const double len = length(across);
        if (!(len > 1e-9)) return;
        t = across / len;
        b = cross(n, t);
    }
    Vec3 toLocal(const Vec3& v) const { return {dot(v, t), dot(v, b), dot(v, n)}; }
    Vec3 toWorld(const Vec3& v) const { return t * v.x + b * v.y + n * v.z; }
};

}  // namespace glint
