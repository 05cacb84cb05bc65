#pragma once
/// Spherical triangles: the solid angle a triangle fills seen from a point, and directions
/// drawn uniformly within it (Arvo 1995, "Stratified Sampling of Spherical Triangles", in the
/// form pbrt-v4 gives it). Sampling a triangular light this way rather than uniformly by area
/// spends no samples on the parts that are far or seen edge-on from the point.

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>

#include "glint/math/sampling.h"
#include "glint/math/vec3.h"

namespace glint {

/// The solid angle of the spherical triangle of unit directions a, b, c (Van Oosterom and
/// Strackee 1983).
inline double sphericalTriangleArea(const Vec3& a, const Vec3& b, const Vec3& c) {
    return std::abs(2 * std::atan2(dot(a, cross(b, c)), 1 + dot(a, b) + dot(a, c) + dot(b, c)));
}

/// A unit direction uniformly distributed over the spherical triangle of unit directions a, b,
/// c, drawn with `u` in [0, 1)^2; none for a degenerate triangle (collinear directions).
inline std::optional<Vec3> sampleSphericalTriangle(const Vec3& a, const Vec3& b, const Vec3& c,
                                                   Point2 u) {
    auto unit = [](const Vec3& v) -> std::optional<Vec3> {
        const double len = length(v);
        if (!(len > 0)) return std::nullopt;
        return v / len;
    };
    // The great circles' normals, and the triangle's angles at a (alpha), b and c.
    const std::optional<Vec3> nab = unit(cross(a, b)), nbc = unit(cross(b, c)),
                              nca = unit(cross(c, a));
    if (!nab || !nbc || !nca) return std::nullopt;
    auto angle = [](const Vec3& x, const Vec3& y) {
        return std::acos(std::clamp(dot(x, y), -1.0, 1.0));
    };
    const double alpha = angle(*nab, -*nca), beta = angle(*nbc, -*nab), gamma = angle(*nca, -*nbc);
    const double area = alpha + beta + gamma - std::numbers::pi;
    if (!(area > 0)) return std::nullopt;

    // The sub-triangle a, b, c' of area u.x * area: c' on the arc from a to c. (The angle
    // sum of the sub-triangle, pi plus its area, enters through phi = that sum - alpha.)
    const double angles = std::numbers::pi + u.x * area;
    const double sinA = std::sin(alpha), cosA = std::cos(alpha);
    const double sinPhi = std::sin(angles) * cosA - std::cos(angles) * sinA;
    const double cosPhi = std::cos(angles) * cosA + std::sin(angles) * sinA;
    const double k1 = cosPhi + cosA;
    const double k2 = sinPhi - sinA * dot(a, b);
    double cosB = (k2 + (k2 * cosPhi - k1 * sinPhi) * cosA) / ((k2 * sinPhi + k1 * cosPhi) * sinA);
    if (!std::isfinite(cosB)) return std::nullopt;
    cosB = std::clamp(cosB, -1.0, 1.0);
    const double sinB = std::sqrt(std::max(1 - cosB * cosB, 0.0));
    const std::optional<Vec3> towardsC = unit(c - a * dot(c, a));
    if (!towardsC) return std::nullopt;
    const Vec3 cPrime = a * cosB + *towardsC * sinB;

    // Then along the arc from b to c', by u.y uniformly in the cosine.
    const double cosTheta = 1 - u.y * (1 - dot(cPrime, b));
    const double sinTheta = std::sqrt(std::max(1 - cosTheta * cosTheta, 0.0));
    const std::optional<Vec3> towardsCPrime = unit(cPrime - b * dot(cPrime, b));
    if (!towardsCPrime) return b;  // the arc has no length
    return unit(b * cosTheta + *towardsCPrime * sinTheta);
}

}  // namespace glint
