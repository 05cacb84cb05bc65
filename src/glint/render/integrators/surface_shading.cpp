#include "glint/render/integrators/surface_shading.h"

#include <cmath>

#include "glint/scene/pbr_material.h"

namespace glint {
namespace {

/// A normal-mapped shading normal `n` that the viewer, at unit direction `wo`, sees past its
/// own horizon (the far slopes of a steep normal map): shading with it would leave those
/// slopes black, because no direction is on the viewer's side of both it and the geometric
/// normal `ng`. It is turned, in the plane of `n` and `wo`, until `wo` stands just above its
/// horizon, keeping the direction of its tilt; a normal the viewer sees from above comes back
/// as it was. The result is on the side of `ng` the viewer is on.
Vec3 facingViewer(const Vec3& n, const Vec3& ng, const Vec3& wo) {
    constexpr double kLift = 0.05;  // the cosine between the view and a turned normal
    const Vec3 side = (dot(n, ng) < 0) == (dot(wo, ng) < 0) ? n : -n;
    const double c = dot(side, wo);
    if (c >= kLift) return side;
    const Vec3 across = side - wo * c;  // the part of the normal across the view
    const double len = length(across);
    if (!(len > 1e-12)) return side;  // along the view: no direction to turn towards
    return wo * kLift + across * (std::sqrt(1 - kLift * kLift) / len);
}

}  // namespace

namespace {

/// The GGX alpha of a glTF roughness.
double ggxAlpha(double roughness) {
    return std::max(roughness * roughness, MetallicRoughness::kMinAlpha);
}

/// glTF's BSDF for the evaluated material `ps` of `pm`, its vectors in `frame`.
MetallicRoughness pbrBsdf(const PbrMaterial& pm, const PbrSurface& ps, const Frame& frame,
                          bool flip) {
    MetallicRoughness b{ps.baseColor,    ps.metallic, ggxAlpha(ps.roughness),
                        ps.transmission, pm.ior,      pm.thickness == 0};
    b.dispersion = pm.dispersion;
    b.specular = ps.specular;
    b.specularColor = ps.specularColor;
    b.anisotropy = ps.anisotropy;
    b.diffuseTransmission = ps.diffuseTransmission;
    b.diffuseTransmissionColor = ps.diffuseTransmissionColor;
    if (ps.iridescence > 0)
        b.iridescence = {ps.iridescence, pm.iridescenceIor, ps.iridescenceThickness};
    if (!(ps.sheenColor == Vec3(0)))
        b.sheen = {ps.sheenColor, std::max(ps.sheenRoughness * ps.sheenRoughness, kMinSheenAlpha)};
    if (ps.clearcoat > 0) {
        Vec3 n = frame.toLocal(flip ? -ps.clearcoatNormal : ps.clearcoatNormal);
        if (!(n.z > 0)) n = Vec3(0, 0, 1);  // a coat normal past the surface: the surface's
        b.coat = {ps.clearcoat, ggxAlpha(ps.clearcoatRoughness), n};
    }
    return b;
}

}  // namespace

SurfaceShading shadeSurface(const Scene& scene, const SurfaceInteraction& si, const Vec3& wo,
                            const std::vector<Bsdf>& bsdfs) {
    const Material& m = scene.materials[si.material];
    SurfaceShading s{Bsdf{}, m.emission, si.n};
    if (m.pbr != 0) {
        const PbrMaterial& pm = scene.pbr(m.pbr);
        const PbrSurface ps = evalSurface(pm, si);
        if (pm.unlit) [[unlikely]] {
            s.emission = ps.baseColor;
            s.bsdf = Bsdf{Lambertian{ps.baseColor}};
            s.frame = Frame(dot(s.normal, si.ng) < 0 ? -s.normal : s.normal);
            s.unlit = true;
            return s;
        }
        s.emission = ps.emission;
        s.normal = ps.normal;
        if (pm.normalTexture.image) s.normal = facingViewer(s.normal, si.ng, wo);
        const bool flip = dot(s.normal, si.ng) < 0;
        const Vec3 ns = flip ? -s.normal : s.normal;
        s.frame = ps.anisotropy > 0 ? Frame(ns, ps.anisotropyDirection) : Frame(ns);
        s.bsdf = pbrBsdf(pm, ps, s.frame, flip);
        return s;
    }
    if (m.texture != 0) {
        Material textured = m;
        textured.diffuse = scene.texture(m.texture).eval(si.hasUv, si.u, si.v, si.p, m.diffuse);
        s.bsdf = bsdfFromMaterial(textured);
    } else {
        s.bsdf = bsdfs[si.material];
    }
    s.frame = Frame(dot(s.normal, si.ng) < 0 ? -s.normal : s.normal);
    return s;
}

std::vector<Bsdf> materialBsdfs(const Scene& scene) {
    std::vector<Bsdf> bsdfs;
    bsdfs.reserve(scene.materials.size());
    for (const Material& m : scene.materials) bsdfs.push_back(bsdfFromMaterial(m));
    return bsdfs;
}

Vec3 volumeTransmittance(const Scene& scene, const SurfaceInteraction& si, const Vec3& origin,
                         const Vec3& dir) {
    const Material& m = scene.materials[si.material];
    if (m.pbr == 0) return Vec3(1);
    const PbrMaterial& pm = scene.pbr(m.pbr);
    if (!std::isfinite(pm.attenuationDistance) || !(pm.thickness > 0) || !(dot(dir, si.ng) > 0))
        return Vec3(1);
    const double travelled = length(si.p - origin);
    auto keep = [&](double x) {
        return x > 0 ? std::exp(std::log(std::min(x, 1.0)) * travelled / pm.attenuationDistance)
                     : 0.0;
    };
    const Vec3& c = pm.attenuationColor;
    return Vec3(keep(c.x), keep(c.y), keep(c.z));
}

bool castsCaustics(const Scene& scene, const Material& m) {
    if (m.pbr != 0) {  // the material's own factors
        const PbrMaterial& pm = scene.pbr(m.pbr);
        if (pm.unlit) return false;  // no path but the camera's meets it
        return MetallicRoughness{pm.baseColor,    pm.metallic, ggxAlpha(pm.roughness),
                                 pm.transmission, pm.ior,      pm.thickness == 0}
            .castsCaustics();
    }
    return m.texture == 0 && bsdfFromMaterial(m).castsCaustics();
}

}  // namespace glint
