#pragma once
/// A spot light: a point light within a cone (light.h's conventions).

#include <iosfwd>
#include <optional>

#include "glint/math/sampling.h"
#include "glint/render/lights/light_sample.h"
#include "glint/render/lights/light_tree.h"

namespace glint {

/// A point light that shines within a cone about `axis`: fully within the angle whose cosine
/// is cosInner, not at all beyond cosOuter, and between them by KHR_lights_punctual's
/// recommended fall-off, the square of the cosine's linear ramp from cosOuter to cosInner.
/// Attenuated with distance as point lights are. A delta light.
struct SpotLight {
    Vec3 position;
    Vec3 axis{0, -1, 0};  ///< Unit, the direction it shines along.
    Vec3 intensity;
    Vec3 attenuation{1, 0, 0};  ///< Constant, linear, quadratic.
    double cosInner = 1, cosOuter = 0.70710678118654752;
    double range = 0;  ///< glTF's range (rangeWindow); 0: none.

    /// The share of the intensity it sends in unit direction `w` (away from the light).
    double falloff(const Vec3& w) const;

    std::optional<LightLiSample> sampleLi(const Vec3& p, Point2 u) const;
    double pdfLi(const Vec3& from, const LightPoint& at, double choice = 1) const;
    std::optional<LightLeSample> sampleLe(Point2 uPos, Point2 uDir,
                                          const LightLeContext& ctx) const;
    LightLePdf pdfLe(const Vec3& origin, const Vec3& n, const Vec3& dir,
                     const LightLeContext& ctx) const;
    /// A point emitting within the outer cone about its axis, of power as a point light's.
    std::optional<LightBounds> bounds() const;
    double infiniteImportance() const { return 0; }
    double lightPassShare() const { return 1; }
    bool tracedByLightPass(const Vec3&) const { return true; }
    bool isDelta() const { return true; }
};
std::ostream& operator<<(std::ostream& out, const SpotLight& l);

}  // namespace glint
