#pragma once
/// A point light with the course's attenuation (light.h's conventions).

#include <iosfwd>
#include <optional>

#include "glint/math/sampling.h"
#include "glint/render/lights/light_sample.h"
#include "glint/render/lights/light_tree.h"
#include "glint/scene/light_spec.h"

namespace glint {

/// Light from a point, of `intensity` over the course's (OpenGL's) attenuation
/// constant + linear d + quadratic d^2 at distance d: a delta light, reached by one direction
/// from each point and by no BSDF sample.
struct PointLight {
    Vec3 position;
    Vec3 intensity;
    Vec3 attenuation{1, 0, 0};  ///< Constant, linear, quadratic.
    double range = 0;           ///< glTF's range (rangeWindow); 0: none.

    /// The direction to the light and its intensity over the attenuation (the brightest finite
    /// light where that rounds to 0), times the range's window; none at the light itself or
    /// beyond its range. Inline: the Whitted integrator's inner loop.
    std::optional<LightLiSample> sampleLi(const Vec3& p, Point2) const {
        Vec3 toLight = position - p;
        double d = length(toLight);
        if (!(d > 0)) return std::nullopt;
        double att = attenuation.x + attenuation.y * d + attenuation.z * d * d;
        if (range > 0) {
            const double w = rangeWindow(d, range);
            if (!(w > 0)) return std::nullopt;
            att /= w;
        }
        return LightLiSample{toLight / d, finiteRadiance(intensity / att), 1, 1, d, true};
    }
    double pdfLi(const Vec3& from, const LightPoint& at, double choice = 1) const;
    std::optional<LightLeSample> sampleLe(Point2 uPos, Point2 uDir,
                                          const LightLeContext& ctx) const;
    LightLePdf pdfLe(const Vec3& origin, const Vec3& n, const Vec3& dir,
                     const LightLeContext& ctx) const;
    /// About 4 pi times its intensity over the attenuation at unit distance; none if black.
    std::optional<LightBounds> bounds() const;
    double infiniteImportance() const { return 0; }
    double lightPassShare() const { return 1; }
    bool tracedByLightPass(const Vec3&) const { return true; }
    bool isDelta() const { return true; }
};
std::ostream& operator<<(std::ostream& out, const PointLight& l);

}  // namespace glint
