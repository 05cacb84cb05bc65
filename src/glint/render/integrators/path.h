#pragma once
/// A unidirectional path tracer (`integrator path`): next-event estimation and BSDF sampling
/// combined by multiple importance sampling with the power heuristic (Veach 1997), unbiased
/// Russian roulette, and every light of the scene (render/lights/light_sampler.h). Materials are
/// the course's, made physical by bsdfFromMaterial (render/bsdfs/bsdf.h); the course's ambient term
/// is not used (the indirect light it stands for is computed), and `emission` makes a surface a
/// light. The path length is the scene's `maxdepth`: the number of scattering events, so 1 is
/// direct lighting only (pbrt's convention; the default is the course's 5). A shadow catcher
/// (Scene::shadowCatcher) ends the camera paths that meet it (render/integrators/shadow_catcher.h).

#include <memory>
#include <mutex>
#include <optional>
#include <vector>

#include "glint/math/sobol.h"
#include "glint/render/bsdfs/bsdf.h"
#include "glint/render/integrators/caustics.h"
#include "glint/render/integrators/integrator.h"
#include "glint/render/integrators/shadow_catcher.h"
#include "glint/render/lights/light_sampler.h"

namespace glint {

class PathIntegrator final : public Integrator {
  public:
    /// How direct light is found: both strategies weighted by multiple importance sampling
    /// (the default), or one alone (each unbiased; for tests and comparisons).
    enum class Strategy { Mis, LightsOnly, BsdfOnly };

    /// The scene must be prepared and outlive the integrator.
    explicit PathIntegrator(const Scene& scene, Strategy strategy = Strategy::Mis);

    Vec3 li(const Ray& ray, const Hit* hit, PathContext& ctx) const override;
    bool usesRandomNumbers() const override { return true; }
    /// The caustics traced from the lights (caustics.h), when the scene asks for them
    /// (Scene::caustics, with the Mis strategy) and has any.
    std::shared_ptr<const LightPassResult> lightPass(
        int begin, int end, uint64_t seed, ThreadPool& pool,
        const std::atomic<bool>* cancel) const override;

  private:
    /// `light` that reached the camera through `bounces` bounces, under the scene's
    /// clampIndirect if it is indirect (two or more).
    Vec3 clamped(const Vec3& light, int bounces) const;

    /// Weight of light a BSDF-sampled ray found on a light that next-event estimation samples
    /// with density `lightPdf` (0: it does not).
    double bsdfWeight(double bsdfPdf, double lightPdf) const;

    /// The render passes' own way on from a smooth surface at `si` (shading frame `frame`), in
    /// the direction of `s` with tint `tint`, where the path went another way: each smooth
    /// surface they meet sends them on along its more likely branch, until a surface that
    /// fills them (film.h), the sky, or `bounces` run out.
    void passesAlone(const SurfaceInteraction& si, const Frame& frame, BsdfSample s, Vec3 tint,
                     const Point2& u, int bounces, SamplePasses& passes) const;

    // Participating media (path_media.cpp).
    /// At point p of medium `med` (id `medium`), which scattered a path arriving from unit
    /// direction wo (towards where it came from) with throughput `beta` after `depth`
    /// bounces: one light sample weighed against the phase function by MIS (added to L), and
    /// the direction the phase function draws next.
    Vec3 scatterInMedium(const Medium& med, uint32_t medium, const Vec3& p, const Vec3& wo,
                         int depth, const Vec3& beta, SobolSampler& sampler, PathContext& ctx,
                         Vec3& L) const;
    /// What a shadow ray lets through: 0 if something other than a medium's boundary is in
    /// the way, else the transmittance of the media it crosses, starting in `medium`.
    Vec3 transmittance(const Ray& ray, uint32_t medium, PathContext& ctx) const;
    /// The medium that a direction `dir` leaving a surface of material `m` (BSDF `bsdf`,
    /// geometric normal `ng`) travels in, when the path arrived in `current`: a refracting
    /// or medium-holding surface is a boundary (its interior inside, the fog outside); others
    /// leave the medium as it was.
    uint32_t mediumAfter(const Material& m, const Bsdf& bsdf, const Vec3& dir, const Vec3& ng,
                         uint32_t current) const;
    /// Medium boundaries a path or shadow ray crosses at most without scattering.
    static constexpr int kMaxCrossings = 256;

    const Scene& scene_;
    LightSampler lights_;
    Strategy strategy_;
    std::vector<Bsdf> bsdfs_;  ///< Of each material (textured ones: with the untextured colour).
    std::optional<ShadowCatcherShading> catcher_;  ///< The scene's shadow catcher, if any.
    /// The light pass, if it is on: then the paths it traces are left to it.
    std::optional<CausticPass> caustics_;
    /// Its recent results, newest last: (begin, end, seed) and the image.
    struct PassResult {
        int begin, end;
        uint64_t seed;
        std::shared_ptr<const LightPassResult> result;
    };
    mutable std::mutex passMutex_;
    mutable std::vector<PassResult> passes_;
};

}  // namespace glint
