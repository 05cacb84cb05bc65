#include "glint/render/whitted.h"

#include <bit>
#include <cmath>
#include <limits>

#include "glint/core/spawn.h"

namespace glint {
namespace {

/// One light's Blinn-Phong term at a point it reaches (N.L > 0, unblocked).
Vec3 lightTerm(const SurfaceInteraction& si, const Vec3& wo, const Material& m,
               const LightSample& ls, double nDotL) {
    Vec3 h = normalize(ls.wi + wo);
    double nDotH = std::max(dot(si.n, h), 0.0);
    return ls.radiance * (m.diffuse * nDotL + m.specular * std::pow(nDotH, m.shininess));
}

/// Whether a hit spawns a mirror ray: specular colour and depth left.
bool reflects(const Material& m, int depth, int maxDepth) {
    return depth < maxDepth && !(m.specular == Vec3(0));
}

}  // namespace

Vec3 WhittedIntegrator::li(const Ray& ray, int depth, RayCounts& counts) const {
    (depth == 0 ? counts.camera : counts.reflection)++;
    Hit hit;
    bool found = scene_.bvh().intersect(ray, hit);
    return shade(ray, found ? &hit : nullptr, depth, counts);
}

Vec3 WhittedIntegrator::shade(const Ray& ray, const Hit* hit, int depth, RayCounts& counts) const {
    if (!hit) return scene_.background.eval(ray.dir);
    SurfaceInteraction si = scene_.primitives.interaction(ray, *hit);
    const Material& m = scene_.materials[si.material];
    const Vec3 wo = -ray.dir;
    Vec3 color = m.ambient + m.emission;
    for (const Light& light : scene_.lights) {
        LightSample ls = light.sample(si.p);
        double nDotL = dot(si.n, ls.wi);
        // A light behind the surface contributes nothing, specular included.
        if (!(nDotL > 0)) continue;
        counts.shadow++;
        if (scene_.bvh().occluded(spawnRay(si.p, ls.wi, scene_.spawnOffset(), ls.distance)))
            continue;
        color += lightTerm(si, wo, m, ls, nDotL);
    }
    if (reflects(m, depth, scene_.maxDepth)) {
        Vec3 r = normalize(reflect(ray.dir, si.n));
        color += m.specular * li(spawnRay(si.p, r, scene_.spawnOffset()), depth + 1, counts);
    }
    return color;
}

void WhittedIntegrator::shade8(const Ray* rays, const HitPacket8& hits, uint32_t active, int depth,
                               Vec3* out, RayCounts& counts) const {
    // The same steps as shade(), lane by lane, with every traced ray in a packet.
    SurfaceInteraction si[8];
    const Material* m[8];
    Vec3 color[8];
    uint32_t hit = 0;
    for (uint32_t lanes = active; lanes; lanes &= lanes - 1) {
        int i = std::countr_zero(lanes);
        if (!(hits.t[i] < std::numeric_limits<float>::infinity())) {
            out[i] = scene_.background.eval(rays[i].dir);
            continue;
        }
        si[i] = scene_.primitives.interaction(rays[i], hits[i]);
        m[i] = &scene_.materials[si[i].material];
        color[i] = m[i]->ambient + m[i]->emission;
        hit |= 1u << i;
    }

    for (const Light& light : scene_.lights) {
        RayPacket8 shadow;
        shadow.active = 0;
        LightSample ls[8];
        double nDotL[8];
        for (uint32_t lanes = hit; lanes; lanes &= lanes - 1) {
            int i = std::countr_zero(lanes);
            ls[i] = light.sample(si[i].p);
            nDotL[i] = dot(si[i].n, ls[i].wi);
            if (!(nDotL[i] > 0)) continue;
            shadow.set(
                i, TraversalRay(spawnRay(si[i].p, ls[i].wi, scene_.spawnOffset(), ls[i].distance)));
            shadow.active = static_cast<uint8_t>(shadow.active | (1u << i));
        }
        if (!shadow.active) continue;
        counts.shadow += static_cast<uint64_t>(std::popcount(shadow.active));
        uint32_t lit = shadow.active & ~scene_.bvh().occluded8(shadow);
        for (; lit; lit &= lit - 1) {
            int i = std::countr_zero(lit);
            color[i] += lightTerm(si[i], -rays[i].dir, *m[i], ls[i], nDotL[i]);
        }
    }

    RayPacket8 mirror;
    mirror.active = 0;
    Ray mirrorRays[8];
    for (uint32_t lanes = hit; lanes; lanes &= lanes - 1) {
        int i = std::countr_zero(lanes);
        if (!reflects(*m[i], depth, scene_.maxDepth)) continue;
        Vec3 r = normalize(reflect(rays[i].dir, si[i].n));
        mirrorRays[i] = spawnRay(si[i].p, r, scene_.spawnOffset());
        mirror.set(i, TraversalRay(mirrorRays[i]));
        mirror.active = static_cast<uint8_t>(mirror.active | (1u << i));
    }
    if (mirror.active) {
        counts.reflection += static_cast<uint64_t>(std::popcount(mirror.active));
        HitPacket8 mirrorHits;
        scene_.bvh().intersect8(mirror, mirrorHits);
        Vec3 reflected[8];
        shade8(mirrorRays, mirrorHits, mirror.active, depth + 1, reflected, counts);
        for (uint32_t lanes = mirror.active; lanes; lanes &= lanes - 1) {
            int i = std::countr_zero(lanes);
            color[i] += m[i]->specular * reflected[i];
        }
    }
    for (uint32_t lanes = hit; lanes; lanes &= lanes - 1) {
        int i = std::countr_zero(lanes);
        out[i] = color[i];
    }
}

}  // namespace glint
