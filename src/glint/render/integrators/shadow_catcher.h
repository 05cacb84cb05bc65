#pragma once
/// How the path tracer shows a shadow catcher (Scene::shadowCatcher): where a camera ray (or a
/// mirror's or glass's continuation of one) meets the plane, it sees the radiance behind the
/// plane times the fraction of the light that reaches the plane there:
///
///     L = Lb(dir) * (1 - O(p) / E)
///
/// Lb is the environment (or background) radiance along the ray, E the irradiance an upward
/// plane receives from the environment and the scene's lights with nothing in the way, O(p) the
/// part of it that the scene blocks at p (all per channel). E's environment part is computed
/// once, by quadrature over the map; O(p) is estimated with one shadow ray towards the
/// environment and one per light (or to one light chosen at random among many), which pass
/// cut-out texels and alpha-blended ones as every shadow ray does (Scene::occluded). Where nothing
/// blocks the light the estimate is exactly 0, so the plane shows the environment exactly,
/// without noise. The environment's direction is drawn over the upper hemisphere in proportion
/// to the map's luminance times cos(theta), texel by texel (for a background colour: by
/// cos(theta)), so that each blocked sample weighs about E itself: in full shadow the estimate
/// is then nearly noiseless too. Lights of emissive surfaces cast no shadow on it, nor does a
/// light whose way to the plane an emitting surface blocks (a point light in its bulb).

#include <optional>
#include <vector>

#include "glint/core/ray.h"
#include "glint/math/distribution.h"
#include "glint/math/sampling.h"
#include "glint/render/integrators/integrator.h"
#include "glint/render/lights/light.h"
#include "glint/scene/scene.h"

namespace glint {

class ShadowCatcherShading {
  public:
    /// For the prepared `scene`, which must have a shadow catcher and outlive this.
    explicit ShadowCatcherShading(const Scene& scene);

    /// The distance along `ray` (in units of its direction) to the plane, when the ray comes
    /// down onto it from above within its extent; none otherwise.
    std::optional<double> intersect(const Ray& ray) const;

    /// The radiance seen at the plane's point `p` by a ray of unit direction `dir`, drawing
    /// the environment direction with `uEnvironment` and, among many lights, the light with
    /// `uLight`. Counts its shadow rays.
    Vec3 radiance(const Vec3& p, const Vec3& dir, Point2 uEnvironment, double uLight,
                  RayCounts& counts) const;

    /// E: the irradiance of an upward plane from the environment (or background) alone.
    Vec3 environmentIrradiance() const { return environmentIrradiance_; }

    /// A direction over the upper hemisphere towards the environment drawn with `u` (see the
    /// file comment), the radiance arriving along it and its density over solid angle; none
    /// where rounding gives a direction of density 0.
    struct EnvironmentSample {
        Vec3 wi, L;
        double pdf = 0;
    };
    std::optional<EnvironmentSample> sampleEnvironment(Point2 u) const;

  private:
    /// What first blocks a light's `shadow` ray: nothing, a surface, or one that emits light
    /// itself (the light's bulb).
    enum class Blocker { None, Surface, Emitter };
    Blocker blocker(const Ray& shadow) const;

    const Scene& scene_;
    std::vector<Light> lights_;  ///< The scene's own (point, spot, directional, quad).
    bool emitters_ = false;      ///< Whether any material emits (a bulb may block a light).
    double height_;
    Vec3 environmentIrradiance_;
    /// With a map: its upper rows' texels, each weighted by the mean luminance of the bilinear
    /// lookup over its cell times the integral of cos(theta) over the cell.
    Distribution2D upper_;
    int upperRows_ = 0;  ///< Rows of the map at least partly above the horizon.
};

/// The irradiance an upward-facing plane receives from `scene`'s environment map, or from its
/// background where it has none: the integral of the radiance times cos(theta) over the upper
/// hemisphere (by quadrature over the map's texels, or exactly for the gradient).
Vec3 upwardIrradiance(const Scene& scene);

}  // namespace glint
