#pragma once
/// Point and directional lights with OpenGL-style attenuation (point lights only).

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
    enum class Kind { Point, Directional };

    Kind kind = Kind::Point;
    Vec3 position;   ///< Point lights, world space.
    Vec3 direction;  ///< Directional lights: unit vector towards the light.
    Vec3 color;
    Vec3 attenuation{1, 0, 0};  ///< Constant, linear, quadratic; point lights only.

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
