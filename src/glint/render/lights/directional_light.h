#pragma once
/// A directional light: parallel light from infinitely far away (light.h's conventions).

#include <iosfwd>
#include <optional>

#include "glint/math/sampling.h"
#include "glint/render/lights/light_sample.h"
#include "glint/render/lights/light_tree.h"

namespace glint {

/// Light of `color` (irradiance on a surface facing it) arriving from `direction` everywhere:
/// the sun. A delta light at infinity.
struct DirectionalLight {
    Vec3 direction;  ///< Unit, towards the light.
    Vec3 color;

    /// Inline: the Whitted integrator's inner loop.
    std::optional<LightLiSample> sampleLi(const Vec3&, Point2) const {
        return LightLiSample{direction, color, 1, 1, kInfinity, true};
    }
    double pdfLi(const Vec3& from, const LightPoint& at, double choice = 1) const;
    std::optional<LightLeSample> sampleLe(Point2 uPos, Point2 uDir,
                                          const LightLeContext& ctx) const;
    LightLePdf pdfLe(const Vec3& origin, const Vec3& n, const Vec3& dir,
                     const LightLeContext& ctx) const;
    std::optional<LightBounds> bounds() const { return std::nullopt; }
    /// pi times the irradiance it gives a surface facing it.
    double infiniteImportance() const;
    double lightPassShare() const { return 1; }
    bool tracedByLightPass(const Vec3&) const { return true; }
    bool isDelta() const { return true; }
};
std::ostream& operator<<(std::ostream& out, const DirectionalLight& l);

}  // namespace glint
