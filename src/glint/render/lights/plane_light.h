#pragma once
/// An emissive infinite plane as a light at infinity (light.h's conventions).

#include <iosfwd>
#include <optional>

#include "glint/math/sampling.h"
#include "glint/render/lights/light_sample.h"
#include "glint/render/lights/light_tree.h"

namespace glint {

/// An emissive plane: infinite, so a light at infinity beside the environment (radiance L over
/// the half of the directions that meet it gives a point in front of it pi L, whatever the
/// distance). Sampled by the cosine about its normal over those directions. It is large: the
/// camera's paths find it well, and the light pass leaves it to them.
struct PlaneLight {
    Vec3 point;   ///< A point on it,
    Vec3 normal;  ///< and its unit normal.
    Vec3 emission;
    bool frontOnly = false;  ///< Emits from the side its normal points to only.

    std::optional<LightLiSample> sampleLi(const Vec3& p, Point2 u) const;
    double pdfLi(const Vec3& from, const LightPoint& at, double choice = 1) const;
    std::optional<LightLeSample> sampleLe(Point2 uPos, Point2 uDir,
                                          const LightLeContext& ctx) const;
    LightLePdf pdfLe(const Vec3& origin, const Vec3& n, const Vec3& dir,
                     const LightLeContext& ctx) const;
    std::optional<LightBounds> bounds() const { return std::nullopt; }
    /// pi times the irradiance it gives a surface facing it: pi^2 L.
    double infiniteImportance() const;
    double lightPassShare() const { return 0; }
    bool tracedByLightPass(const Vec3&) const { return false; }
    bool isDelta() const { return false; }
};
std::ostream& operator<<(std::ostream& out, const PlaneLight& l);

}  // namespace glint
