#include "glint/render/integrators/caustics.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "glint/core/parallel.h"
#include "glint/core/spawn.h"
#include "glint/math/motion.h"
#include "glint/math/rng.h"

namespace glint {
namespace {

/// Pixels per light path of each camera sample index. One path per pixel (pbrt's light
/// tracer) spends more time than it saves: on a glass ball's caustic under a small lamp, 1 in 4
/// measured 1.4x as efficient by relMSE and as clean (fireflies, trimmed relMSE), 1 in 10
/// noisier (docs/performance.md, section 13).
constexpr size_t kPixelsPerPath = 4;

/// Light paths whose photons a pass keeps at most (about 40 bytes each where they land).
constexpr size_t kMaxPhotonPaths = size_t{1} << 22;

/// Light paths per block: each block keeps its splats apart, then blocks are added in order.
constexpr size_t kPathsPerBlock = 4096;

}  // namespace

CausticPass::CausticPass(const Scene& scene, const LightSampler& lights,
                         const std::vector<Bsdf>& bsdfs)
    : scene_(scene), lights_(lights), bsdfs_(bsdfs), filter_(scene.filter) {
    casters_.resize(scene.materials.size());
    bool any = false;
    for (size_t i = 0; i < scene.materials.size(); ++i) {
        casters_[i] = castsCaustics(scene, scene.materials[i]);
        any = any || casters_[i];
    }
    if (!any || !scene.camera || scene.shadowCatcher || lights.empty()) return;
    const CameraSpec& spec = *scene.camera;
    if (spec.apertureRadius > 0) return;
    const Primitives& prims = scene.primitives;
    // The casters' bounds; a caster plane has none, and then the pass stays off.
    for (uint32_t id = prims.boundedCount(); id < prims.size(); ++id)
        if (casters_[prims.materialOf(id)]) return;
    Bounds3f box;
    for (uint32_t id = 0; id < prims.boundedCount(); ++id) {
        const uint32_t m = prims.materialOf(id);
        bool casts = false;
        if (m != Primitives::kMixedMaterials) {
            casts = casters_[m] != 0;
        } else if (prims.isInstance(id)) {
            const Primitives& mesh = prims.sharedMesh(prims.instanceMesh(id));
            for (uint32_t k = 0; k < mesh.size() && !casts; ++k) {
                const uint32_t mk = mesh.materialOf(k);
                casts = mk != Primitives::kMixedMaterials && casters_[mk] != 0;
            }
        }
        if (casts) box.extend(prims.bounds(id));
    }
    if (box.empty()) return;
    const Vec3 lo(box.lo), hi(box.hi);
    center_ = (lo + hi) * 0.5;
    radius_ = std::max(length(hi - lo) * 0.5, 1e-9);
    const Bounds3f all = prims.bounds();
    const Vec3 alo(all.lo), ahi(all.hi);
    const double far =
        (length((alo + ahi) * 0.5 - center_) + length(ahi - alo) * 0.5 + radius_) * 1.01 + 1;
    target_ = LightLeContext{center_, radius_, far, scene.spawnOffset()};
    choice_ = Distribution1D(lights.emissionWeights(center_, radius_));
    camera_.emplace(spec, scene.width, scene.height);
    // Photons are gathered within about two pixels' footprint at the casters' distance.
    const double pixelAngle =
        2 * std::tan(spec.fovyDegrees * std::numbers::pi / 360) / std::max(scene.height, 1);
    photonRadius_ = 2 * pixelAngle * std::max(length(center_ - spec.eye), radius_ * 1e-3);
    filterRadius_ = scene.filter.radius;
    // The filter's integral over one axis (trapezoids), which normalises its profile.
    constexpr int kSteps = 1024;
    double sum = 0;
    for (int i = 0; i < kSteps; ++i) {
        const double x0 = -filterRadius_ + 2 * filterRadius_ * i / kSteps;
        const double x1 = -filterRadius_ + 2 * filterRadius_ * (i + 1) / kSteps;
        sum += 0.5 * (filter_.profile(x0) + filter_.profile(x1)) * (x1 - x0);
    }
    filterNorm_ = sum > 0 ? sum : 1;
    active_ = true;
}

LightPassResult CausticPass::trace(int begin, int end, uint64_t seed, ThreadPool& pool,
                                   const std::atomic<bool>* cancel) const {
    const size_t pixels = static_cast<size_t>(scene_.width) * scene_.height;
    LightPassResult result;
    result.image.assign(pixels, Vec3(0));
    if (!active_ || pixels == 0 || begin >= end) return result;
    const size_t paths = std::max<size_t>(1, pixels / kPixelsPerPath);  // per sample index
    const size_t blocks = (paths + kPathsPerBlock - 1) / kPathsPerBlock;
    const double scale = 1 / static_cast<double>(paths);
    // Photons from the first indices only, up to about kMaxPhotonPaths paths (memory).
    const int photonIndices = std::clamp(static_cast<int>(kMaxPhotonPaths / paths), 1, end - begin);
    std::vector<std::vector<Splat>> splats(blocks);
    std::vector<std::vector<PhotonMap::Photon>> blockPhotons(blocks);
    std::vector<PhotonMap::Photon> photons;
    for (int index = begin; index < end; ++index) {
        const uint64_t indexSeed = mixBits(seed ^ mixBits(0x9e3779b97f4a7c15ULL + index));
        const bool keepPhotons = index < begin + photonIndices;
        parallelFor(pool, 0, blocks, 1, [&](size_t first, size_t last) {
            // Light paths see moving things where they are at the shutter's opening (not yet
            // blurred: docs/animation.md), whichever thread traces them.
            setShutterTime(0);
            for (size_t b = first; b < last; ++b) {
                splats[b].clear();
                blockPhotons[b].clear();
                if (cancel && cancel->load(std::memory_order_relaxed)) continue;
                const size_t p1 = std::min(paths, (b + 1) * kPathsPerBlock);
                for (size_t p = b * kPathsPerBlock; p < p1; ++p)
                    tracePath(mixBits(indexSeed ^ mixBits(p)), splats[b],
                              keepPhotons ? &blockPhotons[b] : nullptr);
            }
        });
        for (size_t b = 0; b < blocks; ++b) {
            for (const Splat& s : splats[b]) result.image[s.pixel] += s.value * scale;
            photons.insert(photons.end(), blockPhotons[b].begin(), blockPhotons[b].end());
        }
        if (cancel && cancel->load(std::memory_order_relaxed)) break;
    }
    // The radius shrinks as photons accumulate (r^2 as their number to the power -1/3, as
    // progressive photon mapping's), so that the estimate converges.
    const double radius = photonRadius_ * std::pow(static_cast<double>(photonIndices), -1.0 / 6);
    result.photons = PhotonMap(std::move(photons), radius,
                               static_cast<double>(paths) * static_cast<double>(photonIndices));
    return result;
}

void CausticPass::tracePath(uint64_t seed, std::vector<Splat>& out,
                            std::vector<PhotonMap::Photon>* photons) const {
    Rng rng(seed);
    auto u2 = [&] { return Point2{rng.uniform(), rng.uniform()}; };
    double pChoice = 0;
    const size_t light = choice_.sampleDiscrete(rng.uniform(), &pChoice);
    const Point2 uPoint = u2(), uDir = u2();
    const Light& source = lights_.light(light);
    std::optional<LightLeSample> emitted = source.sampleLe(uPoint, uDir, target_);
    // Light the pass leaves to the camera's paths (an emissive plane, the sky's dim parts).
    if (!emitted || !source.tracedByLightPass(emitted->L) || !(pChoice > 0)) return;
    const Vec3 emittedBeta = emitted->beta / pChoice;
    Vec3 beta = emittedBeta;
    Ray ray = emitted->ray;
    const double offset = scene_.spawnOffset();
    for (int casters = 0;; ++casters) {
        Hit hit;
        if (!scene_.intersect(ray, hit)) return;
        if (casters == 0) {  // light that meets no caster first is direct light: done
            const uint32_t m = scene_.primitives.materialOf(hit.primId);
            if (m != Primitives::kMixedMaterials && !casters_[m]) return;
        }
        const SurfaceInteraction si = scene_.primitives.interaction(ray, hit);
        if (casters == 0 && emitted->attenuation) {  // the course's fall-off, over the first leg
            const Vec3& a = *emitted->attenuation;
            const double d = length(si.p - ray.origin);
            const double att = a.x + a.y * d + a.z * d * d;
            beta = finiteRadiance(beta * (d * d / att));
        }
        beta = beta * volumeTransmittance(scene_, si, ray.origin, ray.dir);
        const Vec3 toLight = normalize(-ray.dir);
        if (!casters_[si.material]) {
            if (casters == 0) return;  // no caster on the way: direct light, the path tracer's
            connect(si, toLight, beta, out);
            if (photons)
                photons->push_back({Vec3f(si.p), Vec3f(beta), Vec3f(toLight), Vec3f(si.ng),
                                    static_cast<uint32_t>(casters)});
            return;
        }
        // One more caster, then a surface seen by the camera: within the path length.
        if (casters + 2 > scene_.maxDepth) return;
        const SurfaceShading shading = shadeSurface(scene_, si, toLight, bsdfs_);
        const Frame& frame = shading.frame;
        const Vec3 wo = frame.toLocal(toLight);
        const Point2 uLobe = u2(), uDirection = u2();
        std::optional<BsdfSample> bs =
            shading.bsdf.sample(wo, uLobe.x, uDirection, TransportMode::Importance);
        if (!bs || !(bs->pdf > 0)) return;
        const Vec3 next = normalize(frame.toWorld(bs->wi));
        if (!(dot(next, si.ng) * bs->wi.z > 0)) return;  // a leak through the shading normal
        // Light's throughput: the BSDF for importance (no radiance scaling where it refracts)
        // and pbrt's correction for shading normals.
        const double woNg = std::abs(dot(toLight, si.ng)), wiNs = std::abs(bs->wi.z);
        if (!(woNg > 0) || !(wiNs > 0)) return;
        const double shadingCorrection =
            std::abs(wo.z) * std::abs(dot(next, si.ng)) / (woNg * wiNs);
        beta = beta * bs->weight() * shadingCorrection;
        if (beta == Vec3(0)) return;
        // Russian roulette once the light has dimmed.
        const double survive = maxComponent(beta) / maxComponent(emittedBeta);
        if (casters >= 2 && survive < 1) {
            if (rng.uniform() >= survive) return;
            beta = beta / survive;
        }
        ray = spawnRayOffSurface(si.p, si.ng, next, offset);
    }
}

void CausticPass::connect(const SurfaceInteraction& si, const Vec3& toLight, const Vec3& beta,
                          std::vector<Splat>& out) const {
    const Camera& camera = *camera_;
    const Vec3 toEye = camera.eye() - si.p;
    const double distance = length(toEye);
    if (!(distance > 0)) return;
    const Vec3 wc = toEye / distance;
    const Material& m = scene_.materials[si.material];
    // A single-sided glTF surface is not seen from behind (Scene::intersect's culling).
    if (m.pbr != 0 && !scene_.pbr(m.pbr).doubleSided && dot(wc, si.ng) < 0) return;
    const std::optional<Camera::Projection> proj = camera.project(si.p);
    if (!proj) return;
    const double x = proj->x, y = proj->y;
    const double reach = filterRadius_ + 1;  // beyond the image by more: nothing to splat
    if (!(x > -reach && x < scene_.width + reach && y > -reach && y < scene_.height + reach))
        return;
    const int x0 = std::max(0, static_cast<int>(std::floor(x - 0.5 - filterRadius_)));
    const int x1 = std::min(scene_.width - 1, static_cast<int>(std::ceil(x - 0.5 + filterRadius_)));
    const int y0 = std::max(0, static_cast<int>(std::floor(y - 0.5 - filterRadius_)));
    const int y1 =
        std::min(scene_.height - 1, static_cast<int>(std::ceil(y - 0.5 + filterRadius_)));
    if (x0 > x1 || y0 > y1) return;
    // The surface's BSDF as the camera's path would see it there.
    const SurfaceShading shading = shadeSurface(scene_, si, wc, bsdfs_);
    const Frame& frame = shading.frame;
    const Vec3 wo = frame.toLocal(wc), wi = frame.toLocal(toLight);
    if (!(dot(toLight, si.ng) * wi.z > 0)) return;  // as the path tracer's light samples
    const Vec3 f = shading.bsdf.eval(wo, wi);
    if (f == Vec3(0)) return;
    const double wiNg = std::abs(dot(toLight, si.ng));
    if (!(wiNg > 0)) return;
    if (scene_.occluded(shadowRayOffSurface(si.p, si.ng, wc, distance, scene_.spawnOffset())))
        return;
    const Vec3 value = finiteRadiance(
        beta * f * (std::abs(wi.z) / wiNg * std::abs(dot(wc, si.ng)) * proj->importance));
    const double norm = filterNorm_ * filterNorm_;
    for (int py = y0; py <= y1; ++py)
        for (int px = x0; px <= x1; ++px) {
            const double w = filter_.profile(x - (px + 0.5)) * filter_.profile(y - (py + 0.5));
            if (!(w > 0)) continue;
            out.push_back({static_cast<uint32_t>(py * scene_.width + px), value * (w / norm)});
        }
}

}  // namespace glint

namespace glint {

PhotonMap::PhotonMap(std::vector<Photon> photons, double radius, double paths)
    : radius_(radius), scale_(1 / (std::numbers::pi * radius * radius * paths)) {
    if (photons.empty() || !(radius > 0) || !(paths > 0)) return;
    size_t buckets = 1;
    while (buckets < 2 * photons.size()) buckets *= 2;
    mask_ = buckets - 1;
    const double inv = 1 / (2 * radius);
    auto bucketOf = [&](const Photon& ph) {
        return bucket(cell(ph.p.x * inv), cell(ph.p.y * inv), cell(ph.p.z * inv));
    };
    // A counting sort by bucket, stable: the order of the photons within a bucket is theirs.
    start_.assign(buckets + 1, 0);
    for (const Photon& ph : photons) ++start_[bucketOf(ph) + 1];
    for (size_t b = 0; b < buckets; ++b) start_[b + 1] += start_[b];
    photons_.resize(photons.size());
    std::vector<uint32_t> next(start_.begin(), start_.end() - 1);
    for (const Photon& ph : photons) photons_[next[bucketOf(ph)]++] = ph;
}

}  // namespace glint
