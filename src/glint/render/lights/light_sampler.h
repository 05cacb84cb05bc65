#pragma once
/// Chooses among every source of light in a scene (light.h's `Light`s) for a physically based
/// integrator: the point, spot and directional lights, every emissive surface (triangles,
/// meshes, spheres and the other shapes, including the geometry of quad lights; each triangle
/// an instance places is a light of its own), emissive planes, and the environment map or the
/// background. It makes the lights, chooses one per shading point, and leaves the sampling to
/// the light (each light's file says how it samples itself).
///
/// The choice is made in two steps: the lights at infinity (the environment, directional
/// lights, emissive planes) against the others by what each group may give the shading point
/// (the others' light tree's importance, against the irradiance the lights at infinity give in
/// the same units), then within the group: a light at infinity by its irradiance, one of the
/// others through the light tree (render/lights/light_tree.h, pbrt-v4's BVHLightSampler), by
/// its power, distance and orientation as seen from the shading point and its normal.
///
/// A scene's point, spot and directional lights, when it has two to kEachDelta of them, are
/// not chosen but each sampled at every shading point (sampleEach): choosing among coincident
/// or nearby lights of different colours (red, green and blue lamps in one place) shows as
/// colour noise that no choice by power and distance can remove, and a delta light costs one
/// shadow ray and no sampling of its own.

#include <cstdint>
#include <optional>
#include <unordered_map>
#include <vector>

#include "glint/render/lights/light.h"
#include "glint/render/lights/light_tree.h"
#include "glint/scene/scene.h"

namespace glint {

/// A direction towards a light chosen and sampled by LightSampler::sample.
struct LightSample {
    Vec3 wi;  ///< Unit, from the shading point towards the light.
    Vec3 L;   ///< Radiance arriving along -wi (delta lights: intensity over attenuation).
    /// Density of wi over solid angle, times the probability of choosing the light; for delta
    /// lights, just that probability.
    double pdf = 0;
    double distance = 0;  ///< To the point on the light; infinity for distant lights.
    bool delta = false;   ///< A point or directional light: no BSDF sample can reach it.
    /// Whether the light pass (render/integrators/caustics.h) traces light from here
    /// (Light::tracedByLightPass): every light but the emissive planes, the background and the
    /// dim parts of an environment map.
    bool leftToPass = false;
};

class LightSampler {
  public:
    /// Collects the lights of the prepared `scene`, which must outlive the sampler.
    explicit LightSampler(const Scene& scene);

    bool empty() const { return lights_.empty(); }
    size_t size() const { return lights_.size(); }
    /// Light `index` (of size()).
    const Light& light(size_t index) const { return lights_[index]; }

    /// The most point, spot and directional lights sampled each (see the file comment).
    static constexpr size_t kEachDelta = 8;

    /// Calls `f(const LightSample&)` with a sample of each light that is sampled at every
    /// shading point (delta lights, pdf 1), for point `p`.
    template <class F>
    void sampleEach(const Vec3& p, F&& f) const {
        for (uint32_t index : each_) {
            const Light& light = lights_[index];
            if (std::optional<LightLiSample> s = light.sampleLi(p, Point2{0.5, 0.5}))
                f(LightSample{s->wi, s->L, s->pdf, s->distance, s->delta,
                              light.tracedByLightPass(s->L)});
        }
    }
    /// Whether sample() has lights to choose among (besides those sampled each).
    bool choosesAny() const { return lights_.size() > each_.size(); }

    /// Chooses a light with `uLight` for point `p` whose surface normal is `n` (zero: p
    /// receives from every side, behind glass or in a medium) and samples a direction towards
    /// it with `u`. None if nothing arrives (p behind a one-sided emitter, on the light itself,
    /// ...).
    std::optional<LightSample> sample(const Vec3& p, const Vec3& n, double uLight, Point2 u) const;

    /// The density (as LightSample::pdf) with which sample() from `from` with normal `fromN`
    /// would have drawn the direction to `hit`, a point on an emissive surface that a ray from
    /// `from` along unit direction `dir` reached; 0 if that surface is not among the lights.
    double pdfHit(const Vec3& from, const Vec3& fromN, const Vec3& dir, const Hit& hit,
                  const SurfaceInteraction& si) const;

    /// The probability with which sample() chooses light `index` (of size()) for `p`, `n`.
    double choiceProbability(size_t index, const Vec3& p, const Vec3& n) const;

    /// The density (as LightSample::pdf) with which sample() from `from` with normal `fromN`
    /// draws the direction `dir` towards the environment; 0 if the background is black.
    double pdfEnvironment(const Vec3& dir, const Vec3& from, const Vec3& fromN) const;

    /// Radiance of the environment (the map, else the background) arriving from direction `dir`.
    Vec3 environment(const Vec3& dir) const { return scene_.backgroundRadiance(dir); }

    /// environment(dir) and pdfEnvironment(dir, from, fromN) together, the map looked up once.
    Vec3 environment(const Vec3& dir, const Vec3& from, const Vec3& fromN, double* pdf) const;

    /// Whether the light pass traces the light of the environment arriving with `radiance`
    /// (EnvironmentLight::tracedByLightPass: a map's parts much brighter than its mean).
    bool environmentLeftToPass(const Vec3& radiance) const {
        return environment_ != UINT32_MAX && lights_[environment_].tracedByLightPass(radiance);
    }

    /// For tracing light into the sphere of centre `center` and radius `radius` (a part of the
    /// scene that holds everything of interest): a weight for each light, about the power it
    /// sends into the sphere that the light pass traces (Light::lightPassShare).
    std::vector<double> emissionWeights(const Vec3& center, double radius) const;

  private:
    /// The probability of choosing one of the lights at infinity at `p`, `n`.
    double pInfinite(const Vec3& p, const Vec3& n) const;

    const Scene& scene_;
    std::vector<Light> lights_;
    /// The lights at infinity, by index, and their weights' sum; the others are in the tree.
    std::vector<uint32_t> infinite_;
    double infiniteTotal_ = 0;
    /// Of each light: its weight among the lights at infinity (Light::infiniteImportance), 0
    /// for the tree's.
    std::vector<double> infiniteWeight_;
    LightTree tree_;
    std::vector<uint32_t> lightOfTreeLeaf_;  ///< Tree light k is lights_[lightOfTreeLeaf_[k]].
    std::vector<uint32_t> treeLeafOf_;       ///< And back (UINT32_MAX: at infinity).
    /// Light index of each primitive (none: UINT32_MAX); empty if no surface emits.
    std::vector<uint32_t> lightOfPrimitive_;
    /// Light index of each emissive triangle instances place, by (instance id << 32 | its
    /// triangle in the mesh).
    std::unordered_map<uint64_t, uint32_t> lightOfInstanced_;
    uint32_t environment_ = UINT32_MAX;  ///< Index of the environment light, if any.
    std::vector<uint32_t> each_;  ///< The lights sampled at every shading point (sampleEach).
};

}  // namespace glint
