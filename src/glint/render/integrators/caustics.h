#pragma once
/// The light pass of the path tracer: caustics traced from the lights.
///
/// A path tracer finds light focused by glass or mirrors onto a diffuse surface (a caustic)
/// only when a direction it draws at that surface happens to leave through the glass towards a
/// light: for a small light (the sun, a lamp) almost never, and then as a firefly. Traced the
/// other way, from the light through the glass to the surface and from there to the camera,
/// the same light arrives evenly (pbrt's light tracing, the s = k, t = 1 strategies of
/// bidirectional path tracing).
///
/// The two share the work by splitting path space, so that each path is counted once: paths
/// camera -> D -> X1 ... Xk -> light, D a surface that is not a caster left through its
/// non-delta part, X1 ... Xk (k >= 1) surfaces that cast caustics (castsCaustics(): mirrors,
/// glass and metal, smooth or glossy), are this pass's when the camera sees D directly (the
/// light path is joined to the eye: unbiased) or through casters alone (the light path leaves
/// a photon at D, which the camera's path gathers within a radius: Jensen's caustic photon
/// map, biased, its radius shrinking with the samples so that it converges). The path tracer
/// leaves both out (path.cpp), and every other path is its own.
///
/// Each camera sample index of a render stands for one light path per 4 pixels of the image: a
/// light is chosen (by about the power it sends towards the casters), then a point on it, and
/// a direction into the bounding sphere of the casters (light that misses them is no caustic).
/// The path follows casters by their BSDFs (importance transport: no radiance scaling at
/// refraction, pbrt's shading-normal correction) up to the scene's maxdepth, and at the first
/// other surface is joined to the camera's eye and splatted into the pixels whose filter covers
/// where it is seen. The result per pixel is a sum over the sample indices asked for, added to
/// the pixel's sum of camera samples. Deterministic and independent of the thread count: each
/// block of paths keeps its own splats, added in the blocks' order.
///
/// Only where it can work: a pinhole camera (a lens is not sampled), no shadow catcher, and
/// some surface that casts caustics and some light. Otherwise the path tracer keeps every path.

#include <atomic>
#include <cstdint>
#include <optional>
#include <vector>

#include "glint/render/film/filter.h"
#include "glint/render/integrators/light_pass.h"
#include "glint/render/integrators/surface_shading.h"
#include "glint/render/lights/light_sampler.h"
#include "glint/scene/camera.h"

namespace glint {

class ThreadPool;

class CausticPass {
  public:
    /// For the prepared `scene`; `lights` and `bsdfs` are the path tracer's (materialBsdfs),
    /// and all three must outlive the pass.
    CausticPass(const Scene& scene, const LightSampler& lights, const std::vector<Bsdf>& bsdfs);

    /// Whether the pass has work: the scene allows it and has casters and lights.
    bool active() const { return active_; }
    /// Whether material `id` casts caustics (castsCaustics()).
    bool caster(uint32_t id) const { return casters_[id] != 0; }

    /// The light of camera sample indices [begin, end): for each pixel of the image (row by
    /// row, scene width x height), the sum over those indices of its estimate, and the photons
    /// those light paths left on surfaces past casters. `seed` is the render's. Stops early
    /// (returning what it has) when `cancel` becomes true.
    LightPassResult trace(int begin, int end, uint64_t seed, ThreadPool& pool,
                          const std::atomic<bool>* cancel = nullptr) const;

  private:
    struct Splat {
        uint32_t pixel;
        Vec3 value;
    };
    /// Traces one light path drawn from `seed`, appending its splats (not yet divided by the
    /// number of paths) and, if `photons` is not null, the photon it leaves.
    void tracePath(uint64_t seed, std::vector<Splat>& out,
                   std::vector<PhotonMap::Photon>* photons) const;
    /// Joins the surface point `si`, reached by light of throughput `beta` from direction
    /// `toLight`, to the camera.
    void connect(const SurfaceInteraction& si, const Vec3& toLight, const Vec3& beta,
                 std::vector<Splat>& out) const;

    const Scene& scene_;
    const LightSampler& lights_;
    const std::vector<Bsdf>& bsdfs_;
    std::vector<uint8_t> casters_;  ///< By material id.
    bool active_ = false;
    std::optional<Camera> camera_;
    Vec3 center_;  ///< The bounding sphere of the casters.
    double radius_ = 0;
    /// Where light paths are aimed: that sphere, and far beyond its centre, outside the scene,
    /// where light at infinity starts.
    LightLeContext target_;
    Distribution1D choice_;    ///< Of the lights.
    double photonRadius_ = 0;  ///< The photons' gathering radius for a pass of one index.
    FilterSampler filter_;     ///< The scene's pixel filter,
    double filterRadius_ = 0.5, filterNorm_ = 1;  ///< its radius and integral over one axis.
};

}  // namespace glint
