#pragma once
// Quad lights for tests, and the exact irradiance a polygonal light gives.

#include <algorithm>
#include <cmath>
#include <vector>

#include "glint/scene/light_spec.h"

namespace glint::test {

/// Irradiance at `p` (unit normal `n`) from a polygon of uniform unit radiance lying wholly
/// above the tangent plane at `p`: Lambert's formula, E = 1/2 sum_i angle_i (n . unit normal
/// of the plane through p and edge i).
inline double polygonIrradiance(const std::vector<Vec3>& poly, const Vec3& p, const Vec3& n) {
    double sum = 0;
    for (size_t i = 0; i < poly.size(); ++i) {
        Vec3 a = normalize(poly[i] - p), b = normalize(poly[(i + 1) % poly.size()] - p);
        double angle = std::acos(std::clamp(dot(a, b), -1.0, 1.0));
        sum += angle * dot(n, normalize(cross(a, b)));
    }
    return std::abs(sum) / 2;
}

/// A quad light of unit radiance.
inline LightSpec quadLight(const Vec3& corner, const Vec3& e1, const Vec3& e2) {
    LightSpec l;
    l.kind = LightSpec::Kind::Quad;
    l.position = corner;
    l.edge1 = e1;
    l.edge2 = e2;
    l.color = Vec3(1);
    return l;
}

/// The exact irradiance at `p` (unit normal `n`) from the quad light `l` of unit radiance.
inline double quadIrradiance(const LightSpec& l, const Vec3& p, const Vec3& n) {
    return polygonIrradiance(
        {l.position, l.position + l.edge1, l.position + l.edge1 + l.edge2, l.position + l.edge2}, p,
        n);
}

}  // namespace glint::test
