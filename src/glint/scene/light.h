#pragma once
/// Point and directional lights with OpenGL-style attenuation (point lights only).

#include "glint/core/ray.h"

namespace glint {

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

    LightSample sample(const Vec3& p) const {
        if (kind == Kind::Directional) return {direction, kInfinity, color};
        Vec3 toLight = position - p;
        double d = length(toLight);
        double att = attenuation.x + attenuation.y * d + attenuation.z * d * d;
        return {toLight / d, d, color / att};
    }
};

}  // namespace glint
