#pragma once
/// Point and directional lights with OpenGL-style attenuation (point lights only), and
/// parallelogram area lights sampled for soft shadows.

#include <cmath>

#include "glint/core/ray.h"

namespace glint {

/// The largest radiance Glint carries (per channel): far above anything a pixel shows, small
/// enough that products of two stay finite, so no Inf (and no 0 * Inf = NaN) ever arises.
constexpr double kMaxRadiance = 1e30;

/// `c` with each channel clamped to +-kMaxRadiance (NaN, which should never occur, to 0).
inline Vec3 finiteRadiance(const Vec3& c) {
    auto clamp = [](double v) {
        return v > -kMaxRadiance ? (v < kMaxRadiance ? v : kMaxRadiance)
                                 : (v == v ? -kMaxRadiance : 0.0);
    };
    return {clamp(c.x), clamp(c.y), clamp(c.z)};
}

/// What a light delivers at a shading point.
struct LightSample {
    Vec3 wi;          ///< Unit direction from the point towards the light.
    double distance;  ///< Distance to the light; infinity for directional lights.
    Vec3 radiance;    ///< Colour divided by the attenuation.
};

struct Light {
    enum class Kind { Point, Directional, Quad };

    Kind kind = Kind::Point;
    Vec3 position;              ///< Point lights; the corner of quad lights. World space.
    Vec3 direction;             ///< Directional lights: unit vector towards the light.
    Vec3 color;                 ///< Point and directional: intensity. Quad: emitted radiance.
    Vec3 attenuation{1, 0, 0};  ///< Constant, linear, quadratic; point lights only.
    /// Quad lights: the parallelogram position + s edge1 + t edge2, s and t in [0, 1]. It emits
    /// from its front face only, the side cross(edge1, edge2) points to.
    Vec3 edge1, edge2;

    bool isArea() const { return kind == Kind::Quad; }
    /// Quad lights: unit normal of the emitting face and area.
    Vec3 quadNormal() const { return normalize(cross(edge1, edge2)); }
    double quadArea() const { return length(cross(edge1, edge2)); }

    /// What the point (s, t) of a quad light delivers at `p`: the radiance times the solid
    /// angle that the whole light would subtend at that density, L A cos(theta_light) / r^2.
    /// Averaging it over uniform (s, t) and weighting by cos(theta) at `p` estimates the
    /// irradiance. Nothing from behind the light, or from a point on its plane.
    LightSample sampleQuad(const Vec3& p, double s, double t) const {
        Vec3 toLight = position + edge1 * s + edge2 * t - p;
        double d2 = dot(toLight, toLight);
        double d = std::sqrt(d2);
        if (!(d > 0)) return {Vec3(0), 0, Vec3(0)};
        Vec3 wi = toLight / d;
        Vec3 areaNormal = cross(edge1, edge2);  // length = area
        double cosArea = -dot(wi, areaNormal);  // area * cos(theta_light)
        if (!(cosArea > 0)) return {wi, d, Vec3(0)};
        return {wi, d, finiteRadiance(color * (cosArea / d2))};
    }

    /// What reaches `p`. A point light exactly at `p` has no direction and gives nothing
    /// (wi = 0, so N.L = 0); an attenuation that rounds to 0 gives the brightest finite light.
    LightSample sample(const Vec3& p) const {
        if (kind == Kind::Directional) return {direction, kInfinity, color};
        Vec3 toLight = position - p;
        double d = length(toLight);
        if (!(d > 0)) return {Vec3(0), 0, Vec3(0)};
        double att = attenuation.x + attenuation.y * d + attenuation.z * d * d;
        return {toLight / d, d, finiteRadiance(color / att)};
    }
};

}  // namespace glint
