#include "glint/render/integrators/path.h"

#include <algorithm>
#include <cmath>

#include "glint/core/spawn.h"
#include "glint/math/sobol.h"
#include "glint/render/bsdfs/bsdf.h"
#include "glint/render/integrators/media.h"
#include "glint/render/integrators/surface_shading.h"

namespace glint {
namespace {

/// The normal by which the light tree weighs lights for a point of `bsdf` on a surface of
/// geometric normal `ng`: none where light also arrives through the surface (glass,
/// transmission), so that lights on either side count.
Vec3 receivingNormal(const Bsdf& bsdf, const Vec3& ng) { return bsdf.transmits() ? Vec3(0) : ng; }

/// A path's bounces of each kind (Scene::bounces): each count answers whether its bounce was
/// the last its kind allows, after which the path ends at the next surface, as it does after
/// maxdepth bounces in all.
struct BounceCounts {
    int diffuse = 0, glossy = 0, transmission = 0, volume = 0;

    bool surface(BsdfFlags flags, const BounceLimits& limits) {
        if (hasAny(flags, BsdfFlags::Transmission)) return ++transmission >= limits.transmission;
        if (hasAny(flags, BsdfFlags::Diffuse)) return ++diffuse >= limits.diffuse;
        return ++glossy >= limits.glossy;  // glossy and mirror reflections
    }
    bool scattered(const BounceLimits& limits) { return ++volume >= limits.volume; }
};

}  // namespace

PathIntegrator::PathIntegrator(const Scene& scene, Strategy strategy)
    : scene_(scene), lights_(scene), strategy_(strategy) {
    bsdfs_ = materialBsdfs(scene);
    if (scene.shadowCatcher) catcher_.emplace(scene);
    if (scene.caustics && strategy == Strategy::Mis && scene.media.empty()) {
        caustics_.emplace(scene, lights_, bsdfs_);
        if (!caustics_->active()) caustics_.reset();
    }
}

std::shared_ptr<const LightPassResult> PathIntegrator::lightPass(
    int begin, int end, uint64_t seed, ThreadPool& pool, const std::atomic<bool>* cancel) const {
    if (!caustics_ || begin >= end) return nullptr;
    // One pass at a time: a frame rendered in parts on many threads (glint-mpi) asks for the
    // same one from each, and the first computes it while the others wait.
    std::lock_guard lock(passMutex_);
    for (const PassResult& r : passes_)
        if (r.begin == begin && r.end == end && r.seed == seed) return r.result;
    auto result =
        std::make_shared<const LightPassResult>(caustics_->trace(begin, end, seed, pool, cancel));
    if (cancel && cancel->load()) return result;  // cut short: not kept
    // Kept for calls with the same seed (the rounds of an adaptive render's parts ask in
    // turn; a new seed is a new render, or a progressive render's next pass), up to 256 MB.
    std::erase_if(passes_, [&](const PassResult& r) { return r.seed != seed; });
    const size_t bytes = result->image.size() * sizeof(Vec3) +
                         result->photons.size() * sizeof(PhotonMap::Photon) + 1;
    const size_t keep = std::max<size_t>(1, (size_t{256} << 20) / bytes);
    if (passes_.size() >= keep) passes_.erase(passes_.begin());
    passes_.push_back({begin, end, seed, result});
    return result;
}

Vec3 PathIntegrator::clamped(const Vec3& light, int bounces) const {
    const double limit = scene_.clampIndirect;
    if (bounces < 2 || !(limit > 0)) return light;  // direct light, or no clamp
    const double most = maxComponent(light);
    return most > limit ? light * (limit / most) : light;
}

double PathIntegrator::bsdfWeight(double bsdfPdf, double lightPdf) const {
    switch (strategy_) {
        case Strategy::Mis:
            return powerHeuristic(bsdfPdf, lightPdf);
        case Strategy::LightsOnly:
            return lightPdf > 0 ? 0 : 1;  // lights not sampled count in full
        default:
            return 1;
    }
}

void PathIntegrator::passesAlone(const SurfaceInteraction& si, const Frame& frame, BsdfSample s,
                                 Vec3 tint, const Point2& u, int bounces,
                                 SamplePasses& passes) const {
    const double offset = scene_.spawnOffset();
    Vec3 p = si.p, ng = si.ng, dir = normalize(frame.toWorld(s.wi));
    int crossings = 0;
    for (; bounces > 0; --bounces) {
        tint = tint * min(s.weight(), Vec3(1));
        const Ray ray = spawnRayOffSurface(p, ng, dir, offset);
        Hit hit;
        const bool found = scene_.intersect(ray, hit);
        if (catcher_) {
            std::optional<double> t = catcher_->intersect(ray);
            if (t && (!found || *t < hit.t)) {  // as the path sees it (li)
                passes.albedo = tint;
                passes.normal = Vec3(0, 1, 0);
                return;
            }
        }
        if (!found) return;  // the sky: no albedo, no normal
        const SurfaceInteraction next = scene_.primitives.interaction(ray, hit);
        p = next.p;
        ng = next.ng;
        if (scene_.materials[next.material].interface) {  // crossed unchanged
            if (++crossings > kMaxCrossings) return;
            ++bounces;
            continue;
        }
        const SurfaceShading shading = shadeSurface(scene_, next, -ray.dir, bsdfs_);
        if (std::optional<Vec3> albedo = shading.bsdf.passAlbedo()) {
            passes.albedo = tint * *albedo;
            passes.normal = dot(shading.normal, ray.dir) > 0 ? -shading.normal : shading.normal;
            return;
        }
        std::optional<BsdfSample> more =
            shading.bsdf.sample(shading.frame.toLocal(-ray.dir), 0.5, u);
        if (!more || !(more->pdf > 0)) return;
        s = *more;
        dir = normalize(shading.frame.toWorld(s.wi));
    }
}

Vec3 PathIntegrator::li(const Ray& cameraRay, const Hit* cameraHit, PathContext& ctx) const {
    SobolSampler sampler(ctx.pixelSeed, ctx.sampleIndex);
    const double offset = scene_.spawnOffset();
    Vec3 L(0), beta(1);
    bool specularBounce = false;
    double bsdfPdf = 0;  // density of the direction the last bounce drew
    Vec3 from, fromN;    // where it left from, and the normal the light tree saw there
    Ray ray = cameraRay;
    Hit hit;
    bool found = cameraHit != nullptr;
    if (found) hit = *cameraHit;
    // The render passes (film.h): filled at the first surface that is not a perfect mirror or
    // glass, through the tint of those before it.
    SamplePasses* passes = ctx.passes;
    Vec3 passTint(1);
    // With the light pass on (caustics.h): -1 once the path is not one it traces, else the
    // casters met since the surface the camera sees, which left through its non-delta part.
    int castersSinceSeen = -1;
    bool throughCasters = true;  // every surface so far casts caustics
    // The medium the path travels in (Scene::medium; 0: none), and the medium boundaries it
    // crossed without scattering.
    uint32_t medium = scene_.fog;
    int crossings = 0;
    int channel = -1;  // the colour channel a dispersing surface chose; -1: all
    BounceCounts bounces;
    bool lastBounce = false;  // the last bounce used up its kind's limit

    for (int depth = 0;; ++depth) {
        // ==== Shadow catcher: seen by camera rays and their specular continuations only ====
        if (catcher_ && (depth == 0 || specularBounce)) [[unlikely]] {
            std::optional<double> t = catcher_->intersect(ray);
            if (t && (!found || *t < hit.t)) {
                if (passes) {  // the plane shows the background: an upward "surface" of albedo 1
                    passes->albedo = passTint;
                    passes->normal = Vec3(0, 1, 0);
                    if (depth == 0) passes->depth = *t * length(ray.dir);
                }
                const Point2 uEnvironment = sampler.get2D();
                const double uLight = sampler.get2D().x;
                L += beta * catcher_->radiance(ray.origin + ray.dir * *t, normalize(ray.dir),
                                               uEnvironment, uLight, ctx.counts);
                break;
            }
        }
        // ==== Medium: it may scatter or absorb before the surface (or the sky) ====
        if (medium != 0) [[unlikely]] {
            const Medium& med = scene_.medium(medium);
            const MediumEvent e = sampleMedium(med, ray, found ? hit.t : kInfinity, ctx.rng, beta);
            if (e.kind == MediumEvent::Kind::Absorbed) break;
            if (e.kind == MediumEvent::Kind::Scattered) {
                const Vec3 p = ray.origin + ray.dir * e.t;
                const Vec3 wo = -normalize(ray.dir);
                if (passes) [[unlikely]] {  // a medium's point: its albedo, facing the view
                    const Vec3 st = med.sigmaT();
                    passes->albedo = passTint * Vec3(st.x > 0 ? med.sigmaS.x / st.x : 0,
                                                     st.y > 0 ? med.sigmaS.y / st.y : 0,
                                                     st.z > 0 ? med.sigmaS.z / st.z : 0);
                    passes->normal = wo;
                    if (depth == 0) passes->depth = length(p - ray.origin);
                    passes = nullptr;
                }
                if (depth >= scene_.maxDepth || lastBounce) break;
                const Vec3 next = scatterInMedium(med, medium, p, wo, depth, beta, sampler, ctx, L);
                lastBounce = bounces.scattered(scene_.bounces);
                bsdfPdf = HenyeyGreenstein{med.g}.eval(wo, next);
                specularBounce = false;
                castersSinceSeen = -1;
                throughCasters = false;
                from = p;
                fromN = Vec3(0);
                const double survive = maxComponent(beta);
                if (depth >= 1 && survive < 1) {
                    if (ctx.rng.uniform() >= survive) break;
                    beta = beta / survive;
                }
                ray = Ray{p, next, 0, kInfinity};
                hit = Hit{};
                found = scene_.intersect(ray, hit);
                continue;
            }
        }
        // ==== Escaped: the environment, weighed against light sampling ====
        if (!found) {
            // Seen by the camera or through a mirror it counts in full: no density is needed.
            Vec3 light(0);
            // Its bright parts, found through casters from a seen surface: the light pass's.
            auto passTraces = [&](const Vec3& le) {
                return castersSinceSeen > 0 && lights_.environmentLeftToPass(le);
            };
            if (depth == 0 || specularBounce) {
                const Vec3 le = lights_.environment(ray.dir);
                if (!passTraces(le)) light = beta * le;
            } else {
                double lightPdf = 0;
                const Vec3 le = lights_.environment(ray.dir, from, fromN, &lightPdf);
                if (!(le == Vec3(0)) && !passTraces(le))
                    light = beta * le * bsdfWeight(bsdfPdf, lightPdf);
            }
            L += clamped(light, depth);  // light found at depth d came through d bounces
            break;
        }
        // ==== The surface: a medium's boundary is crossed; anything else is shaded ====
        const SurfaceInteraction si = scene_.primitives.interaction(ray, hit);
        const Material& m = scene_.materials[si.material];
        if (m.interface) [[unlikely]] {  // only a medium's boundary: cross it unchanged
            if (++crossings > kMaxCrossings) break;
            medium = dot(ray.dir, si.ng) < 0 ? m.interior : scene_.fog;
            ray = spawnRayOffSurface(si.p, si.ng, normalize(ray.dir), offset);
            hit = Hit{};
            found = scene_.intersect(ray, hit);
            --depth;  // not a scattering event
            continue;
        }

        // Absorption inside a volume, paid on leaving it (Beer-Lambert over the segment).
        beta = beta * volumeTransmittance(scene_, si, ray.origin, ray.dir);
        SurfaceShading shading = shadeSurface(scene_, si, -ray.dir, bsdfs_);
        // A dispersing volume refracts each colour its own way: the path follows one channel
        // (chosen at the first such surface, weighted by 3 to stay unbiased) from there on.
        if (shading.bsdf.disperses()) [[unlikely]] {
            if (channel < 0) {
                channel = std::min(2, static_cast<int>(ctx.rng.uniform() * 3));
                Vec3 only(0);
                only[channel] = 3;
                beta = beta * only;
            }
            shading.bsdf.selectChannel(channel);
        }
        const Bsdf& bsdf = shading.bsdf;
        const Vec3& emission = shading.emission;
        const Vec3& shadingNormal = shading.normal;
        // ==== Render passes: albedo, normal, depth at the first surface that fills them ====
        if (passes) [[unlikely]] {
            if (depth == 0) passes->depth = length(si.p - ray.origin);
            if (std::optional<Vec3> albedo = bsdf.passAlbedo()) {
                passes->albedo = passTint * *albedo;
                passes->normal = dot(shadingNormal, ray.dir) > 0 ? -shadingNormal : shadingNormal;
                passes = nullptr;  // filled
            }
        }

        // ==== The light pass's share: which paths it traces instead ====
        // Whether the path is one the light pass traces (any light it meets through casters
        // but an emissive plane, LightSample::leftToPass).
        const bool caster = caustics_ && caustics_->caster(si.material);
        const bool leftToPass =
            castersSinceSeen > 0 && hit.primId < scene_.primitives.boundedCount();
        if (castersSinceSeen >= 0) castersSinceSeen = caster ? castersSinceSeen + 1 : -1;
        // The surface the camera sees, directly or through casters alone: the light pass
        // brings the light that reaches it through casters.
        const bool seenHere = caustics_ && throughCasters && !caster;
        throughCasters = throughCasters && caster;

        // ==== Emission: light the surface sends along the path, weighed against light samples ====
        if (!(emission == Vec3(0)) && (!m.frontEmissionOnly || dot(ray.dir, si.ng) < 0) &&
            !leftToPass) {
            const Vec3 light =
                depth == 0 || specularBounce
                    ? beta * emission
                    : beta * emission *
                          bsdfWeight(bsdfPdf, lights_.pdfHit(from, fromN, ray.dir, hit, si));
            L += clamped(light, depth);
        }
        if (shading.unlit) [[unlikely]]
            break;  // its colour, as is, and nothing beyond
        // A path that runs out of bounces ends black, inside glass too: ending it in the
        // environment along its way was measured more wrong (docs/performance.md, "Bounce
        // limits"); the model mode's deeper transmission limit is what keeps glass clear.
        if (depth >= scene_.maxDepth || lastBounce) break;

        const Frame& frame = shading.frame;
        const Vec3 wo = frame.toLocal(-ray.dir);
        // A direction whose side of the shading surface differs from its side of the
        // geometric one would leak light through the surface (shading normals, normal maps):
        // such directions carry nothing.
        auto consistent = [&](const Vec3& wWorld, const Vec3& wLocal) {
            return dot(wWorld, si.ng) * wLocal.z > 0;
        };

        // ==== Photons: light through casters, gathered where the camera sees through them ====
        // Seen through casters: the light that reaches it through casters is the photons'
        // (the light pass's splats bring it where the camera sees the surface directly).
        if (seenHere && depth > 0 && ctx.lightPass && depth < scene_.maxDepth) [[unlikely]] {
            const uint32_t most = static_cast<uint32_t>(scene_.maxDepth - 1 - depth);
            const Vec3 gathered =
                ctx.lightPass->photons.gather(si.p, si.ng, most, [&](const Vec3& wi) {
                    const Vec3 w = frame.toLocal(wi);
                    const double cosG = std::abs(dot(wi, si.ng));
                    if (!consistent(wi, w) || !(cosG > 1e-6)) return Vec3(0);
                    return bsdf.eval(wo, w) * (std::abs(w.z) / cosG);
                });
            L += clamped(beta * gathered, depth + 2);
        }

        // ==== Light sample: next-event estimation, weighed against the BSDF's density ====
        // Three pairs of dimensions per bounce: (light, lobe), the point on the light, the
        // BSDF's direction; Russian roulette takes the sample's own random numbers.
        const Point2 uChoices = sampler.get2D();
        const double uLight = uChoices.x;
        const Point2 uLightPoint = sampler.get2D();
        const Vec3 receiver = receivingNormal(bsdf, si.ng);
        auto addLight = [&](const LightSample& ls) {
            // BSDF sampling alone cannot reach delta lights: they are sampled in every mode.
            // Past casters from a seen surface, most lights are the light pass's.
            if (ls.L == Vec3(0) || !(ls.delta || strategy_ != Strategy::BsdfOnly) ||
                (castersSinceSeen > 0 && ls.leftToPass))
                return;
            Vec3 wi = frame.toLocal(ls.wi);
            if (!consistent(ls.wi, wi)) wi = Vec3(0);
            Vec3 f = bsdf.eval(wo, wi) * std::abs(wi.z);
            if (f == Vec3(0)) return;
            ctx.counts.shadow++;
            const Vec3 tr =
                transmittance(shadowRayOffSurface(si.p, si.ng, ls.wi, ls.distance, offset),
                              mediumAfter(m, bsdf, ls.wi, si.ng, medium), ctx);
            if (tr == Vec3(0)) return;
            double w = ls.delta || strategy_ == Strategy::LightsOnly
                           ? 1
                           : powerHeuristic(ls.pdf, bsdf.pdf(wo, wi));
            L += clamped(beta * f * tr * ls.L * (w / ls.pdf), depth + 1);
        };
        if (!lights_.empty() && !bsdf.specularOnly()) {
            lights_.sampleEach(si.p, addLight);  // a few delta lights, each (light_sampler.h)
            if (std::optional<LightSample> ls = lights_.sample(si.p, receiver, uLight, uLightPoint))
                addLight(*ls);
        }

        // ==== BSDF sample: the next direction, and the passes' way on from smooth surfaces ====
        const double uLobe = uChoices.y;
        const Point2 uDir = sampler.get2D();
        std::optional<BsdfSample> bs = bsdf.sample(wo, uLobe, uDir);
        if (!bs || !(bs->pdf > 0)) break;
        const Vec3 next = normalize(frame.toWorld(bs->wi));
        if (!consistent(next, bs->wi)) break;
        beta = beta * bs->weight();
        if (passes) [[unlikely]] {
            // A smooth surface: the passes go on along its more likely branch (the refraction of
            // glass at most angles), whichever the path took, so that the albedo does not take
            // the noise of the path's choice. Where the path went the other way they go on
            // alone (one ray and shading per surface, no light).
            const std::optional<BsdfSample> likely = bsdf.sample(wo, 0.5, uDir);
            if (likely && likely->pdf > 0 && !(likely->wi == bs->wi)) {
                passesAlone(si, frame, *likely, passTint, uDir, scene_.maxDepth - depth, *passes);
                passes = nullptr;
            } else {
                passTint = passTint * min(bs->weight(), Vec3(1));
            }
        }
        if (beta == Vec3(0)) break;
        lastBounce = bounces.surface(bs->flags, scene_.bounces);
        specularBounce = bs->isSpecular();
        if (seenHere && !specularBounce) castersSinceSeen = 0;
        bsdfPdf = bs->pdf;
        from = si.p;
        fromN = receiver;

        // ==== Russian roulette, then the next ray ====
        // Russian roulette from the second bounce on: a path of throughput below 1 survives
        // with probability equal to it, and is reweighted so the estimate stays unbiased.
        double survive = maxComponent(beta);
        if (depth >= 1 && survive < 1) {
            if (ctx.rng.uniform() >= survive) break;
            beta = beta / survive;
        }

        medium = mediumAfter(m, bsdf, next, si.ng, medium);
        ray = spawnRayOffSurface(si.p, si.ng, next, offset);
        ctx.counts.reflection++;
        hit = Hit{};
        found = scene_.intersect(ray, hit);
    }
    return finiteRadiance(L, ctx.counts);
}

}  // namespace glint
