#include "glint/render/integrators/whitted.h"

#include <cmath>
#include <numbers>
#include <optional>

#include "glint/core/spawn.h"
#include "glint/render/bsdfs/optics.h"

namespace glint {
namespace {

/// Branches at transmissive surfaces whose weight falls below this are not traced: they
/// cannot move an 8-bit pixel by more than about a quarter of a level.
constexpr double kMinBranchWeight = 1e-3;

/// The GGX lobe's share of lightTerm(), scaled by pi like the course's diffuse term (which is
/// kd N.L without the 1/pi of a Lambertian BRDF): pi D G2 / (4 N.V).
[[gnu::noinline]] double ggxSpecular(const SurfaceInteraction& si, const Vec3& wo, const Vec3& wi,
                                     double roughness) {
    double nDotV = dot(si.n, wo);
    Vec3 sum = wi + wo;
    double len = length(sum);
    if (!(nDotV > 0 && len > 0)) return 0;
    Ggx ggx{roughness};
    Frame f(si.n);
    Vec3 h = f.toLocal(sum / len);
    return std::numbers::pi * ggx.d(h) * ggx.g2(f.toLocal(wo), f.toLocal(wi)) / (4 * nDotV);
}

/// Density over solid angle with which indirect() draws the GGX lobe's reflected ray `wi` at
/// `si` for the viewer `wo`: the visible-normal density over 4 (wo.h), G1(wo) D(h) / (4 N.V).
[[gnu::noinline]] double ggxReflectionPdf(const SurfaceInteraction& si, const Vec3& wo,
                                          const Vec3& wi, double roughness) {
    Frame f(dot(si.n, wo) >= 0 ? si.n : -si.n);
    Vec3 o = f.toLocal(wo), i = f.toLocal(wi);
    Vec3 sum = o + i;
    double len = length(sum);
    if (!(o.z > 0 && i.z > 0 && len > 0)) return 0;
    Ggx ggx{roughness};
    return ggx.g1(o) * ggx.d(sum / len) / (4 * o.z);
}

/// One light's specular and diffuse term at a point it reaches from unit direction `wi`
/// (N.L > 0, unblocked) with `radiance` (the light's colour over the attenuation, or an area
/// light's L / pdf): Blinn-Phong as the course has it, or the GGX lobe for rough materials.
inline Vec3 lightTerm(const SurfaceInteraction& si, const Vec3& wo, const Material& m,
                      const Vec3& wi, const Vec3& radiance, double nDotL) {
    if (m.roughness > 0)
        return radiance * (m.diffuse * nDotL + m.specular * ggxSpecular(si, wo, wi, m.roughness));
    Vec3 sum = wi + wo;
    double len = length(sum);
    // When the light is exactly opposite the viewer (seen through a back face), L + V is zero
    // and has no direction: there is no highlight then.
    double nDotH = len > 0 ? std::max(dot(si.n, sum / len), 0.0) : 0.0;
    return radiance * (m.diffuse * nDotL + m.specular * std::pow(nDotH, m.shininess));
}

}  // namespace

int areaLightGrid(const Scene& scene, int spp) {
    if (scene.lightSamples > 0) return scene.lightSamples;
    // 16 shadow rays per area light and pixel in all: 4 x 4 at one sample per pixel, fewer
    // per sample as samples grow (the pixel's samples jitter them anyway).
    return std::max(1, static_cast<int>(std::lround(4 / std::sqrt(std::max(spp, 1)))));
}

WhittedIntegrator::WhittedIntegrator(const Scene& scene, int spp)
    : scene_(scene), areaGrid_(areaLightGrid(scene, spp)) {
    for (const Material& m : scene.materials) {
        // Media's interface surfaces let shadow rays through too (unchanged: Whitted renders
        // no media).
        anyTransmissive_ = anyTransmissive_ || m.transmissive() || m.interface;
        usesRandomNumbers_ = usesRandomNumbers_ || m.roughness > 0;
    }
    for (const LightSpec& l : scene.lights) {
        lights_.push_back(lightFromSpec(l));
        anyAreaLights_ = anyAreaLights_ || l.isArea();
    }
    usesRandomNumbers_ = usesRandomNumbers_ || anyAreaLights_;
}

Vec3 WhittedIntegrator::trace(const Ray& ray, int depth, double weight, PathContext& ctx) const {
    (depth == 0 ? ctx.counts.camera : ctx.counts.reflection)++;
    Hit hit;
    bool found = scene_.intersect(ray, hit, depth == 0);
    return shade(ray, found ? &hit : nullptr, depth, weight, ctx);
}

Vec3 WhittedIntegrator::transmittance(const Vec3& p, const Vec3& wi, double distance,
                                      RayCounts& counts) const {
    counts.shadow++;
    Ray ray = spawnRay(p, wi, scene_.spawnOffset(), distance);
    if (!anyTransmissive_) return scene_.occluded(ray) ? Vec3(0) : Vec3(1);
    // Walk the surfaces along the segment, filtering through each transmissive one. The walk
    // ends: every step moves past a hit, and a segment crosses few surfaces in practice.
    Vec3 t(1);
    for (int crossings = 0; crossings < 256; ++crossings) {
        Hit hit;
        if (!scene_.intersect(ray, hit)) return t;
        SurfaceInteraction si = scene_.primitives.interaction(ray, hit);
        const Material& m = scene_.materials[si.material];
        if (!m.transmissive() && !m.interface) return Vec3(0);
        if (!m.interface) {
            bool entering = dot(wi, si.ng) < 0;
            double cosI = std::abs(dot(wi, si.ng));
            t = t * m.transmission * (1 - fresnelDielectric(cosI, entering ? 1 / m.ior : m.ior));
        }
        if (maxComponent(t) <= 0) return Vec3(0);
        double travelled = length(si.p - ray.origin);
        Ray next = spawnRay(si.p, wi, scene_.spawnOffset(), ray.tMax - travelled);
        if (!(next.tMax > next.tMin)) return t;
        ray = next;
        counts.shadow++;
    }
    return Vec3(0);
}

[[gnu::always_inline]] inline void WhittedIntegrator::directLight(const SurfaceInteraction& si,
                                                                  const Vec3& wo, const Material& m,
                                                                  bool glossyRay, Vec3& color,
                                                                  PathContext& ctx) const {
    for (const Light& light : lights_) {
        if (!light.isDelta()) {
            areaLight(light, si, wo, m, glossyRay, color, ctx);
            continue;
        }
        std::optional<LightLiSample> ls = light.sampleLi(si.p, {});
        if (!ls) continue;
        // Copies, so that the sample stays in registers (its address never escapes).
        const Vec3 wi = ls->wi, radiance = ls->L;
        const double distance = ls->distance;
        double nDotL = dot(si.n, wi);
        // A light behind the surface contributes nothing, specular included.
        if (!(nDotL > 0)) continue;
        if (!anyTransmissive_) {  // the course's case, kept lean
            ctx.counts.shadow++;
            if (scene_.occluded(spawnRay(si.p, wi, scene_.spawnOffset(), distance))) continue;
            color += lightTerm(si, wo, m, wi, radiance, nDotL);
            continue;
        }
        Vec3 t = transmittance(si.p, wi, distance, ctx.counts);
        if (t == Vec3(0)) continue;
        color += lightTerm(si, wo, m, wi, radiance, nDotL) * t;
    }
}

void WhittedIntegrator::areaLight(const Light& light, const SurfaceInteraction& si, const Vec3& wo,
                                  const Material& m, bool glossyRay, Vec3& color,
                                  PathContext& ctx) const {
    // An n x n stratified, jittered grid over the parallelogram, each point weighted by
    // L / pdf = L * invPdf, which is the course's L * (A cos(theta_light) / r^2) to the bit.
    const int n = areaGrid_;
    const double inv = 1.0 / (n * n);
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            double s = (i + static_cast<double>(ctx.rng.uniform())) / n;
            double tt = (j + static_cast<double>(ctx.rng.uniform())) / n;
            std::optional<LightLiSample> ls = light.sampleLi(si.p, {s, tt});
            if (!ls) continue;
            double nDotL = dot(si.n, ls->wi);
            Vec3 radiance = finiteRadiance(ls->L * ls->invPdf);
            if (!(nDotL > 0) || radiance == Vec3(0)) continue;
            // Back off at the light's end too: the light's own surface lies there.
            Vec3 onLight = si.p + ls->wi * ls->distance;
            double end = ls->distance - spawnOffset(onLight, scene_.spawnOffset());
            Vec3 t = transmittance(si.p, ls->wi, end, ctx.counts);
            if (t == Vec3(0)) continue;
            radiance = radiance * inv;
            if (!glossyRay) {
                color += lightTerm(si, wo, m, ls->wi, radiance, nDotL) * t;
                continue;
            }
            // The GGX lobe's reflected ray finds this light too: weigh the two estimates of its
            // highlight by multiple importance sampling (n x n light samples against one ray).
            double pl = n * n * ls->pdf;
            double w = powerHeuristic(pl, ggxReflectionPdf(si, wo, ls->wi, m.roughness));
            Vec3 diffuse = m.diffuse * nDotL;
            Vec3 specular = m.specular * (ggxSpecular(si, wo, ls->wi, m.roughness) * w);
            color += radiance * (diffuse + specular) * t;
        }
}

Vec3 WhittedIntegrator::indirect(const Ray& ray, const SurfaceInteraction& si, const Material& m,
                                 int depth, double weight, PathContext& ctx) const {
    const double offset = scene_.spawnOffset();
    if (m.transmissive()) {
        // Which side the ray arrives from follows the geometric normal (outward for closed
        // shapes and consistently wound meshes); the shading normal is turned to that side.
        bool entering = dot(ray.dir, si.ng) < 0;
        Vec3 n = entering ? si.n : -si.n;
        if (!(dot(ray.dir, n) < 0)) n = entering ? si.ng : -si.ng;
        double eta = entering ? 1 / m.ior : m.ior;
        double fresnel = fresnelDielectric(-dot(ray.dir, n), eta);
        Vec3 reflectW = m.specular + m.transmission * fresnel;
        Vec3 transmitW = m.transmission * (1 - fresnel);
        Vec3 color(0);
        auto branch = [&](const Vec3& w, const Vec3& dir) {
            double next = weight * maxComponent(w);
            if (!(next >= kMinBranchWeight) || ctx.branchRaysLeft <= 0) return;
            --ctx.branchRaysLeft;
            color += w * trace(spawnRay(si.p, dir, offset), depth + 1, next, ctx);
        };
        branch(reflectW, normalize(reflect(ray.dir, n)));
        Vec3 refracted;
        if (fresnel < 1 && refract(ray.dir, n, eta, refracted)) branch(transmitW, refracted);
        return color;
    }
    if (m.specular == Vec3(0)) return Vec3(0);
    // One direction from the GGX lobe per visit: the pixel's samples average the lobe.
    Vec3 wo = -ray.dir;
    Frame f(dot(si.n, wo) >= 0 ? si.n : -si.n);
    Ggx ggx{m.roughness};
    Vec3 woL = f.toLocal(wo);
    double u1 = ctx.rng.uniform(), u2 = ctx.rng.uniform();
    Vec3 h = ggx.sampleVisibleNormal(woL, u1, u2);
    Vec3 wiL = h * (2 * dot(woL, h)) - woL;
    double g = ggx.g1(wiL);
    if (!(g > 0)) return Vec3(0);
    Vec3 wi = normalize(f.toWorld(wiL));
    Ray next = spawnRay(si.p, wi, offset);
    ctx.counts.reflection++;
    Hit hit;
    bool found = scene_.intersect(next, hit);
    if (found && anyAreaLights_) {
        // An area light's surface: its emission weighed against the light's own samples
        // (areaLight()), on their scale (pi times the physical one, like the course's terms).
        SurfaceInteraction at = scene_.primitives.interaction(next, hit);
        const Material& lm = scene_.materials[at.material];
        if (lm.frontEmissionOnly && lm.diffuse == Vec3(0) && lm.specular == Vec3(0) &&
            !lm.transmissive()) {
            Vec3 c = lm.ambient;
            if (dot(wi, at.ng) < 0) {
                double pl = 0;
                for (const Light& light : lights_)
                    if (!light.isDelta()) pl += light.pdfLi(si.p, LightPoint{at.p, at.ng, wi});
                double pb = ggx.g1(woL) * ggx.d(h) / (4 * woL.z);
                c += lm.emission *
                     (std::numbers::pi * powerHeuristic(pb, areaGrid_ * areaGrid_ * pl));
            }
            return m.specular * g * finiteRadiance(c, ctx.counts);
        }
    }
    return m.specular * g * shade(next, found ? &hit : nullptr, depth + 1, weight, ctx);
}

[[gnu::always_inline]] inline Vec3 WhittedIntegrator::shadeHit(
    const Ray& ray, const SurfaceInteraction& si, const SurfaceInteraction& lit, const Material& m,
    bool frontOnly, int depth, double weight, PathContext& ctx) const {
    // Area lights' surfaces emit from their front face only (shadeSpecial's case).
    Vec3 color = frontOnly && !(dot(ray.dir, si.ng) < 0) ? m.ambient : m.ambient + m.emission;
    // Whether indirect() traces the GGX lobe's reflected ray.
    const bool glossyRay =
        m.roughness > 0 && depth < scene_.maxDepth && !m.transmissive() && !(m.specular == Vec3(0));
    directLight(lit, -ray.dir, m, glossyRay, color, ctx);
    if (depth < scene_.maxDepth) {
        if (m.transmissive() || m.roughness > 0) {
            color += indirect(ray, si, m, depth, weight, ctx);
        } else if (!(m.specular == Vec3(0))) {
            // The course's mirror, inline: the common case.
            Vec3 r = normalize(reflect(ray.dir, si.n));
            color +=
                m.specular * trace(spawnRay(si.p, r, scene_.spawnOffset()), depth + 1, weight, ctx);
        }
    }
    return finiteRadiance(color, ctx.counts);
}

Vec3 WhittedIntegrator::li(const Ray& ray, const Hit* hit, PathContext& ctx) const {
    if (ctx.passes && hit) [[unlikely]] {
        // The first surface's: the course's shading has no chains for passes to follow.
        const SurfaceInteraction si = scene_.primitives.interaction(ray, *hit);
        const Material& m = scene_.materials[si.material];
        Vec3 diffuse = m.diffuse;
        if (m.texture != 0)
            diffuse = scene_.texture(m.texture).eval(si.hasUv, si.u, si.v, si.p, m.diffuse);
        ctx.passes->albedo = max(min(diffuse + m.specular, Vec3(1)), Vec3(0));
        ctx.passes->normal = dot(si.n, ray.dir) > 0 ? -si.n : si.n;
        ctx.passes->depth = length(si.p - ray.origin);
    }
    return shade(ray, hit, 0, 1, ctx);
}

[[gnu::always_inline]] inline Vec3 WhittedIntegrator::shade(const Ray& ray, const Hit* hit,
                                                            int depth, double weight,
                                                            PathContext& ctx) const {
    if (!hit) return scene_.backgroundRadiance(ray.dir);
    return shadeSurface(ray, *hit, depth, weight, ctx);
}

Vec3 WhittedIntegrator::shadeSurface(const Ray& ray, const Hit& hit, int depth, double weight,
                                     PathContext& ctx) const {
    SurfaceInteraction si = scene_.primitives.interaction(ray, hit);
    const Material& m = scene_.materials[si.material];
    if (m.interface) [[unlikely]]  // a medium's boundary, unseen: what lies beyond it
        return trace(spawnRay(si.p, normalize(ray.dir), scene_.spawnOffset()), depth, weight, ctx);
    if (m.texture != 0 || m.frontEmissionOnly || m.pbr != 0)
        return shadeSpecial(ray, si, m, depth, weight, ctx);
    return shadeHit(ray, si, si, m, false, depth, weight, ctx);
}

Vec3 WhittedIntegrator::shadeSpecial(const Ray& ray, const SurfaceInteraction& si,
                                     const Material& m, int depth, double weight,
                                     PathContext& ctx) const {
    // The back face of a double-sided glTF material is lit as its front (the glTF
    // specification: its normals are turned towards the viewer). Only the lights see the
    // turned normals: refraction tells entering from leaving by the geometric normal as it is.
    // An unlit surface shows its colour, unshaded (only camera rays find it: Scene::cutOut).
    if (m.pbr != 0 && scene_.pbr(m.pbr).unlit) [[unlikely]]
        return evalSurface(scene_.pbr(m.pbr), si).baseColor;
    SurfaceInteraction lit = si;
    if (m.pbr != 0 && scene_.pbr(m.pbr).doubleSided && dot(ray.dir, si.ng) > 0) {
        lit.n = -si.n;
        lit.ng = -si.ng;
    }
    if (m.texture == 0) return shadeHit(ray, si, lit, m, m.frontEmissionOnly, depth, weight, ctx);
    Material textured = m;
    textured.diffuse = scene_.texture(m.texture).eval(si.hasUv, si.u, si.v, si.p, m.diffuse);
    return shadeHit(ray, si, lit, textured, m.frontEmissionOnly, depth, weight, ctx);
}

}  // namespace glint
