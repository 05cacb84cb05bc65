#pragma once
/// The lights a scene declares, as its file says them: point lights with OpenGL-style
/// attenuation, spot lights, directional lights, and parallelogram (quad) area lights. A
/// description only: integrators light scenes with render/lights/light.h's `Light`, made from
/// these (lightFromSpec) and from the scene's emissive surfaces and environment.

#include <cmath>
#include <iosfwd>

#include "glint/math/vec3.h"

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

/// glTF's window of a light of `range` at distance d (KHR_lights_punctual's recommendation):
/// max(min(1 - (d / range)^4, 1), 0), 1 where range is 0 (none).
inline double rangeWindow(double d, double range) {
    if (!(range > 0)) return 1;
    const double x = d / range, x2 = x * x;
    return x2 * x2 >= 1 ? 0 : 1 - x2 * x2;
}

struct LightSpec {
    enum class Kind { Point, Spot, Directional, Quad };

    Kind kind = Kind::Point;
    Vec3 position;              ///< Point and spot lights; the corner of quad lights. World space.
    Vec3 direction;             ///< Directional lights: unit vector towards the light.
    Vec3 color;                 ///< Point, spot, directional: intensity. Quad: emitted radiance.
    Vec3 attenuation{1, 0, 0};  ///< Constant, linear, quadratic; point and spot lights only.
    /// Point and spot lights: glTF's range, beyond which they light nothing, reached smoothly
    /// (rangeWindow); 0: no limit.
    double range = 0;
    /// Spot lights: the unit axis they shine along (away from the light), and the cosines of
    /// the angles from it within which they shine fully (inner) and beyond which not at all
    /// (outer), as glTF's KHR_lights_punctual gives them.
    Vec3 axis{0, -1, 0};
    double cosInner = 1, cosOuter = 0.70710678118654752;  // glTF's defaults: 0 and 45 degrees
    /// Quad lights: the parallelogram position + s edge1 + t edge2, s and t in [0, 1]. It emits
    /// from its front face only, the side cross(edge1, edge2) points to.
    Vec3 edge1, edge2;

    bool isArea() const { return kind == Kind::Quad; }
    /// Quad lights: the parallelogram's area.
    double quadArea() const { return length(cross(edge1, edge2)); }
    /// Point, spot and directional lights: a single direction reaches each point, which no
    /// BSDF sample can hit.
    bool isDelta() const { return kind != Kind::Quad; }
};
/// "LightSpec{point at (x, y, z), colour (r, g, b), attenuation (c, l, q)}", and so on.
std::ostream& operator<<(std::ostream& out, const LightSpec& l);

}  // namespace glint
