// The path tracer in participating media (path.h): scattering at a medium's points, shadow
// rays through media and their boundaries, and which medium a path is in.

#include "glint/core/spawn.h"
#include "glint/render/integrators/media.h"
#include "glint/render/integrators/path.h"

namespace glint {

uint32_t PathIntegrator::mediumAfter(const Material& m, const Bsdf& bsdf, const Vec3& dir,
                                     const Vec3& ng, uint32_t current) const {
    if (scene_.media.empty()) return current;
    if (m.interior == 0 && !bsdf.relativeEta()) return current;
    return dot(dir, ng) < 0 ? m.interior : scene_.fog;
}

Vec3 PathIntegrator::transmittance(const Ray& shadowRay, uint32_t medium, PathContext& ctx) const {
    if (scene_.media.empty()) return scene_.occluded(shadowRay) ? Vec3(0) : Vec3(1);
    const double offset = scene_.spawnOffset();
    const Vec3 target = shadowRay.origin + shadowRay.dir * shadowRay.tMax;
    const bool finite = std::isfinite(shadowRay.tMax);
    Ray ray = shadowRay;
    Vec3 tr(1);
    for (int crossings = 0; crossings <= kMaxCrossings; ++crossings) {
        Hit hit;
        const bool found = scene_.intersect(ray, hit);
        if (medium != 0)
            tr = tr *
                 mediumTransmittance(scene_.medium(medium), ray, found ? hit.t : ray.tMax, ctx.rng);
        if (!found || tr == Vec3(0)) return tr;
        const SurfaceInteraction si = scene_.primitives.interaction(ray, hit);
        const Material& m = scene_.materials[si.material];
        if (!m.interface) return Vec3(0);
        medium = dot(ray.dir, si.ng) < 0 ? m.interior : scene_.fog;
        const Vec3 dir = normalize(ray.dir);
        ray = finite ? shadowRayOffSurface(si.p, si.ng, dir, length(target - si.p), offset)
                     : spawnRayOffSurface(si.p, si.ng, dir, offset);
    }
    return Vec3(0);
}

Vec3 PathIntegrator::scatterInMedium(const Medium& med, uint32_t medium, const Vec3& p,
                                     const Vec3& wo, int depth, const Vec3& beta,
                                     SobolSampler& sampler, PathContext& ctx, Vec3& L) const {
    const HenyeyGreenstein phase{med.g};
    const Point2 uLight = sampler.get2D(), uLightPoint = sampler.get2D();
    auto addLight = [&](const LightSample& ls) {
        if (ls.L == Vec3(0) || !(ls.delta || strategy_ != Strategy::BsdfOnly)) return;
        const double f = phase.eval(wo, ls.wi);
        ctx.counts.shadow++;
        Ray shadow{p, ls.wi, 0, kInfinity};
        if (std::isfinite(ls.distance)) {
            const Vec3 target = p + ls.wi * ls.distance;
            shadow.tMax = ls.distance - spawnOffset(target, scene_.spawnOffset());
        }
        const Vec3 tr = transmittance(shadow, medium, ctx);
        if (!(tr == Vec3(0)) && f > 0) {
            const double w =
                ls.delta || strategy_ == Strategy::LightsOnly ? 1 : powerHeuristic(ls.pdf, f);
            L += clamped(beta * tr * ls.L * (f * w / ls.pdf), depth + 1);
        }
    };
    if (!lights_.empty()) {
        lights_.sampleEach(p, addLight);  // a few delta lights, each (light_sampler.h)
        if (std::optional<LightSample> ls = lights_.sample(p, Vec3(0), uLight.x, uLightPoint))
            addLight(*ls);
    }
    return phase.sample(wo, sampler.get2D());
}

}  // namespace glint
