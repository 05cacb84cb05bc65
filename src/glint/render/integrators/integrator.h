#pragma once
/// The integrator seam: what turns a camera ray into radiance. The renderer (renderer.h) knows
/// only this interface and makes one virtual call per camera sample; traversal and shading
/// inside an integrator are plain calls. Integrators are chosen by name (`integrator NAME` in a
/// scene, `--integrator NAME` on the command line); docs/design.md says where a new one goes.

#include <atomic>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "glint/math/rng.h"
#include "glint/render/film/film.h"
#include "glint/render/integrators/light_pass.h"
#include "glint/scene/scene.h"

namespace glint {

class ThreadPool;

/// Rays traced, by kind, and radiance values that were not finite where an integrator
/// produced them (a bug: they are repaired before the film, and reported by `--stats`).
struct RayCounts {
    uint64_t camera = 0, shadow = 0, reflection = 0;
    uint64_t nonFinite = 0;  ///< Radiance values with a NaN or infinite channel, repaired.

    uint64_t total() const { return camera + shadow + reflection; }
    RayCounts& operator+=(const RayCounts& o) {
        camera += o.camera;
        shadow += o.shadow;
        reflection += o.reflection;
        nonFinite += o.nonFinite;
        return *this;
    }
};

/// What one camera sample carries through its tree of rays: its own random numbers (seeded
/// from pixel, sample and seed, so images do not depend on threads) and its ray counts.
struct PathContext {
    Rng rng;
    RayCounts& counts;
    /// Refracted and reflected rays a sample may still spawn at transmissive surfaces, where
    /// every hit splits in two: bounds the work of any scene at any depth.
    int branchRaysLeft = 4096;
    /// The pixel's seed and the sample's index within the pixel, for integrators that draw
    /// low-discrepancy sample values (math/sobol.h) rather than take ctx.rng's.
    uint64_t pixelSeed = 0;
    uint32_t sampleIndex = 0;
    /// Where the integrator reports the sample's render passes (film.h: albedo, normal and
    /// depth); null when no pass is asked for.
    SamplePasses* passes = nullptr;
    /// The integrator's light pass for this render (Integrator::lightPass), if it made one.
    const LightPassResult* lightPass = nullptr;
};

/// `c` if every channel is finite and within +-kMaxRadiance (scene/light_spec.h); otherwise `c`
/// clamped there, NaN channels set to 0, and counted in `counts.nonFinite` if any channel was
/// NaN or infinite. Every integrator passes the radiance it returns through this.
Vec3 repairRadiance(const Vec3& c, RayCounts& counts);
inline Vec3 finiteRadiance(const Vec3& c, RayCounts& counts) {
    auto ok = [](double v) { return v > -kMaxRadiance && v < kMaxRadiance; };
    if (ok(c.x) && ok(c.y) && ok(c.z)) [[likely]]
        return c;
    return repairRadiance(c, counts);
}

/// What an integrator may depend on besides the scene.
struct IntegratorOptions {
    int spp = 1;  ///< Camera samples per pixel (the Whitted integrator's area-light grid).
};

class Integrator {
  public:
    virtual ~Integrator() = default;

    /// Radiance arriving along the camera ray `ray`, given its closest hit in the scene (null:
    /// it hits nothing), which the renderer found (for a whole packet at once). Counts the rays
    /// it traces into ctx.counts, but not `ray` itself.
    virtual Vec3 li(const Ray& ray, const Hit* hit, PathContext& ctx) const = 0;

    /// Whether li() draws random numbers from ctx.rng; if not, samples need no seeded
    /// PathContext::rng (it costs a hash per sample).
    virtual bool usesRandomNumbers() const = 0;

    /// Light this integrator leaves to a pass over the whole image of its own (the path
    /// tracer's caustics, render/integrators/caustics.h), for camera sample indices [begin, end):
    /// light for the renderer to add to each pixel's sum of samples, and photons for li() to gather
    /// (PathContext::lightPass); null if it leaves nothing. `seed` is the render's seed; `pool`
    /// the threads to trace on; it stops early if `cancel` becomes true. May be called from
    /// several threads at once, and keeps recent results for calls that ask again (a frame
    /// rendered in many small parts).
    virtual std::shared_ptr<const LightPassResult> lightPass(
        int begin, int end, uint64_t seed, ThreadPool& pool,
        const std::atomic<bool>* cancel) const {
        (void)begin, (void)end, (void)seed, (void)pool, (void)cancel;
        return nullptr;
    }
};

/// One integrator Glint has.
struct IntegratorInfo {
    std::string_view name;     ///< As in `integrator NAME`.
    std::string_view summary;  ///< One line, for --help and messages.
    std::unique_ptr<Integrator> (*make)(const Scene& scene, const IntegratorOptions& options);
};

/// Every integrator, the default (`whitted`) first.
const std::vector<IntegratorInfo>& integrators();

/// The integrator called `name`, or null if there is none.
const IntegratorInfo* findIntegrator(std::string_view name);

/// "whitted" (or "whitted, path"): the names, for messages.
std::string integratorNameList();

/// The integrator `scene.integrator` names, for the prepared `scene` (which must outlive it).
/// Throws RenderError if there is no such integrator.
std::unique_ptr<Integrator> makeIntegrator(const Scene& scene, const IntegratorOptions& options);

}  // namespace glint
