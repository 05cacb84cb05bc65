#include "glint/render/whitted.h"

#include <cmath>

#include "glint/core/spawn.h"

namespace glint {
namespace {

/// One light's Blinn-Phong term at a point it reaches (N.L > 0, unblocked). When the light is
/// exactly opposite the viewer (seen through a back face), L + V is zero and has no direction:
/// there is no highlight then.
Vec3 lightTerm(const SurfaceInteraction& si, const Vec3& wo, const Material& m,
               const LightSample& ls, double nDotL) {
    Vec3 sum = ls.wi + wo;
    double len = length(sum);
    double nDotH = len > 0 ? std::max(dot(si.n, sum / len), 0.0) : 0.0;
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
    return finiteRadiance(color);
}

}  // namespace glint
