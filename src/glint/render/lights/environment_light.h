#pragma once
/// The environment (a map, or the background) as a light at infinity (light.h's conventions).

#include <iosfwd>
#include <optional>

#include "glint/math/sampling.h"
#include "glint/render/lights/light_sample.h"
#include "glint/render/lights/light_tree.h"
#include "glint/scene/environment.h"
#include "glint/scene/scene.h"

namespace glint {

/// Light arriving from every direction: an environment map (scene/environment.h), sampled by
/// its luminance, or the background's gradient, sampled uniformly over the sphere. Its bright
/// parts (a sun's or a lamp's disc in a map, several times its mean) are small lights that
/// paths through glass hardly find: the light pass traces those; the rest is the camera
/// paths'.
struct EnvironmentLight {
    const EnvironmentMap* map = nullptr;  ///< Null: the background.
    Background background;
    double importance = 0;  ///< pi times the irradiance its mean radiance gives: pi^2 L.
    /// The luminance above which the light pass traces its light (infinite without a map),
    /// and the share of the map's power above it.
    double passThreshold = kInfinity, passShare = 0;

    /// The light of `map` (null: of `background`).
    static EnvironmentLight make(const EnvironmentMap* map, const Background& background);

    /// Radiance arriving from unit direction `dir`; with `pdf`, also choice times the density
    /// with which sampleLi draws it, from one look-up of the map.
    Vec3 radiance(const Vec3& dir, double* pdf = nullptr, double choice = 1) const;

    std::optional<LightLiSample> sampleLi(const Vec3& p, Point2 u) const;
    double pdfLi(const Vec3& from, const LightPoint& at, double choice = 1) const;
    std::optional<LightLeSample> sampleLe(Point2 uPos, Point2 uDir,
                                          const LightLeContext& ctx) const;
    LightLePdf pdfLe(const Vec3& origin, const Vec3& n, const Vec3& dir,
                     const LightLeContext& ctx) const;
    std::optional<LightBounds> bounds() const { return std::nullopt; }
    double infiniteImportance() const { return importance; }
    double lightPassShare() const { return passShare; }
    bool tracedByLightPass(const Vec3& L) const { return luminance(L) > passThreshold; }
    bool isDelta() const { return false; }
};
std::ostream& operator<<(std::ostream& out, const EnvironmentLight& l);

}  // namespace glint
