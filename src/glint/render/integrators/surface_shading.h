#pragma once
/// What a physically based integrator needs at a surface point: its BSDF, emission and shading
/// normal (textures, glTF materials and normal maps evaluated), the absorption of a glTF volume
/// paid along a segment inside it, and which surfaces cast caustics. Shared by the path tracer
/// (path.h) and the light pass that traces caustics from the lights (caustics.h), so that both
/// see the same surfaces.

#include <vector>

#include "glint/render/bsdfs/bsdf.h"
#include "glint/scene/scene.h"

namespace glint {

struct SurfaceShading {
    Bsdf bsdf;
    Vec3 emission;
    Vec3 normal;  ///< Unit shading normal (as interpolated or normal-mapped; either side).
    /// The BSDF's local frame: its z the shading normal turned to the geometric normal's
    /// side (so that the side a direction lies on, inside or outside a dielectric, is the
    /// geometry's), its x the direction of anisotropy where a material has one.
    Frame frame{Vec3(0, 0, 1)};
    /// An unlit surface (PbrMaterial::unlit): `emission` is its colour, which ends the path;
    /// the BSDF only gives the render passes its albedo.
    bool unlit = false;
};

/// The shading of `si`, seen from unit direction `wo` (towards the viewer, or towards where a
/// light path came from), and its frame. `bsdfs` holds each material's untextured BSDF
/// (bsdfFromMaterial).
SurfaceShading shadeSurface(const Scene& scene, const SurfaceInteraction& si, const Vec3& wo,
                            const std::vector<Bsdf>& bsdfs);

/// Each material's untextured BSDF, by material id.
std::vector<Bsdf> materialBsdfs(const Scene& scene);

/// The fraction of light that a glTF volume (KHR_materials_volume's attenuation) lets through
/// along a ray from `origin` that leaves it at `si`; 1 elsewhere (Beer-Lambert).
Vec3 volumeTransmittance(const Scene& scene, const SurfaceInteraction& si, const Vec3& origin,
                         const Vec3& dir);

/// Whether surfaces of material `m` cast caustics: mirrors, glass, metal and glTF metal or
/// glass that are smooth or glossy (GGX alpha below 0.1, a glTF roughness below 0.32; at most
/// 1% diffuse), judged by the material's own factors (not its textures) so that the answer is
/// the same at every point of it. Light that reaches a camera-seen surface through such
/// surfaces alone is left to the light pass (caustics.h) by the path tracer.
bool castsCaustics(const Scene& scene, const Material& m);

}  // namespace glint
