#pragma once
/// glTF 2.0's metallic-roughness material, evaluated per texel (docs/scene-format.md,
/// "Physically based materials"): the factors and textures of the specification's material
/// model and of the extensions Glint reads (KHR_texture_transform, KHR_materials_emissive_strength,
/// KHR_materials_transmission, KHR_materials_ior, KHR_materials_volume). glTF files, OBJ's PBR
/// extensions and the scene file's `pbr` maps all describe their materials with it. A Material
/// names one by id (Material::pbr); the path tracer evaluates it at every hit (evalSurface)
/// and scatters by render/bsdfs/bsdf.h's MetallicRoughness. The Whitted integrator uses the flat
/// Material the loaders also fill in.

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>

#include "glint/geometry/primitives.h"
#include "glint/math/vec3.h"
#include "glint/scene/texture.h"

namespace glint {

/// One texture of a material: an image, how it wraps on each axis, which texture coordinates
/// it reads and their transform.
struct TextureSlot {
    std::shared_ptr<const TextureImage> image;  ///< Null: the slot is empty.
    TextureWrap wrapS = TextureWrap::Repeat, wrapT = TextureWrap::Repeat;
    uint8_t texCoord = 0;  ///< 0: the first set of texture coordinates (TEXCOORD_0), 1: the second.
    /// KHR_texture_transform as a 2 x 3 matrix (row major) applied to glTF's coordinates, whose
    /// v runs down the image (v_gltf = 1 - v): (s, t) = M (u, 1 - v, 1). Identity by default.
    std::array<double, 6> transform{1, 0, 0, 0, 1, 0};

    explicit operator bool() const { return image != nullptr; }
    bool operator==(const TextureSlot&) const =
        default;  ///< The same image (pointer) and settings.
    /// The transform from glTF's offset, rotation (radians) and scale, as KHR_texture_transform
    /// composes them: translation * rotation * scale.
    void setTransform(double offsetU, double offsetV, double rotation, double scaleU,
                      double scaleV);
    /// The filtered value at hit `si` (bilinear, its wrap modes, its coordinate set and
    /// transform); `fallback` when the slot is empty or the hit lacks those coordinates.
    Rgba sample(const SurfaceInteraction& si, Rgba fallback = {Vec3(1), 1}) const;
};

enum class AlphaMode : uint8_t {
    Opaque,  ///< Alpha is ignored.
    Mask,    ///< Texels of alpha below the cutoff are cut out: rays pass as if nothing were there.
    Blend,   ///< A hit counts with probability alpha: rays pass with probability 1 - alpha.
};

struct PbrMaterial {
    Vec3 baseColor{1};  ///< Linear; times baseColorTexture and the vertex colour.
    double alpha = 1;   ///< Times the texture's and the vertex colour's alpha.
    TextureSlot baseColorTexture;
    double metallic = 1, roughness = 1;  ///< Perceptual roughness: GGX alpha = roughness^2.
    /// Roughness in green, metalness in blue, both linear (multiplying the factors).
    TextureSlot metallicRoughnessTexture;
    /// Separate maps (MTL's map_Pr and map_Pm, the scene file's): the red channel, linear,
    /// multiplies the roughness and the metalness.
    TextureSlot roughnessTexture, metallicTexture;
    /// Tangent-space normals (x right along the tangent, y along the bitangent), linear.
    TextureSlot normalTexture;
    double normalScale = 1;  ///< Scales the map's x and y.
    Vec3 emissive{0};        ///< Radiance (emissiveFactor times emissive strength), linear.
    TextureSlot emissiveTexture;
    AlphaMode alphaMode = AlphaMode::Opaque;
    double alphaCutoff = 0.5;
    /// Lit on both faces; false: the back face is not seen by camera rays (glTF's back-face
    /// culling), though it still casts shadows and is seen in reflections.
    bool doubleSided = false;
    /// KHR_materials_unlit: camera rays see the base colour (factor, texture, vertex colour) as
    /// it is, unshaded; every other ray passes through (no shadow, no reflection, no light
    /// from it), as Blender's glTF importer maps it for Cycles.
    bool unlit = false;
    /// Seen by camera rays; false (a glTF material's extras, gltf_materials.cpp) lets them through,
    /// as Cycles hides Blender's area lights from the camera while reflections and shadows still
    /// see them.
    bool cameraVisible = true;
    /// KHR_materials_transmission: the fraction of the dielectric part that is transmitted
    /// (times the red channel of transmissionTexture).
    double transmission = 0;
    TextureSlot transmissionTexture;
    /// KHR_materials_dispersion: 20 / the Abbe number of a refracting volume (0: none).
    double dispersion = 0;
    double ior = 1.5;  ///< KHR_materials_ior; sets the dielectric's F0 = ((ior - 1) / (ior + 1))^2.
    /// KHR_materials_volume: a thickness above 0 makes the mesh the boundary of a refracting
    /// volume; 0 (the default) a thin wall that transmits without bending.
    double thickness = 0;
    /// Beer-Lambert absorption inside the volume: light keeps attenuationColor after
    /// attenuationDistance (infinite: no absorption).
    Vec3 attenuationColor{1};
    double attenuationDistance = std::numeric_limits<double>::infinity();

    /// KHR_materials_specular: the dielectric's f90 and a factor on its f0 (times the alpha
    /// channel of specularTexture), and a colour on its f0 (times specularColorTexture, sRGB).
    double specular = 1;
    TextureSlot specularTexture;
    Vec3 specularColor{1};
    TextureSlot specularColorTexture;
    /// KHR_materials_clearcoat: the coat's weight (times the red channel of its texture), its
    /// perceptual roughness (times the green channel of its texture) and its own normal map
    /// (without one, the coat follows the interpolated normal, not the base's normal map).
    double clearcoat = 0;
    TextureSlot clearcoatTexture;
    double clearcoatRoughness = 0;
    TextureSlot clearcoatRoughnessTexture;
    TextureSlot clearcoatNormalTexture;
    double clearcoatNormalScale = 1;
    /// KHR_materials_sheen: its colour (times the texture's, sRGB) and perceptual roughness
    /// (times the alpha channel of its texture).
    Vec3 sheenColor{0};
    TextureSlot sheenColorTexture;
    double sheenRoughness = 0;
    TextureSlot sheenRoughnessTexture;
    /// KHR_materials_anisotropy: the strength (times the texture's blue channel), and the
    /// direction: the tangent turned by `anisotropyRotation` radians towards the bitangent,
    /// after the texture's red and green channels (a direction in tangent space) turn it.
    double anisotropy = 0, anisotropyRotation = 0;
    TextureSlot anisotropyTexture;
    /// KHR_materials_iridescence: the film's weight (times the red channel of its texture),
    /// index, and thickness in nanometres: the maximum, or between the minimum and maximum by
    /// the green channel of the thickness texture.
    double iridescence = 0;
    TextureSlot iridescenceTexture;
    double iridescenceIor = 1.3, iridescenceThicknessMin = 100, iridescenceThicknessMax = 400;
    TextureSlot iridescenceThicknessTexture;
    /// KHR_materials_diffuse_transmission: the share of the diffuse lobe sent through the
    /// surface (times the alpha channel of its texture), and its colour (times the texture's,
    /// sRGB).
    double diffuseTransmission = 0;
    TextureSlot diffuseTransmissionTexture;
    Vec3 diffuseTransmissionColor{1};
    TextureSlot diffuseTransmissionColorTexture;

    /// Whether some rays pass through it: alpha masked or blended, or unlit (seen by camera
    /// rays only).
    bool cutsOut() const { return alphaMode != AlphaMode::Opaque || unlit; }
    bool operator==(const PbrMaterial&) const = default;
};

/// A material evaluated at a hit (before the side of the hit is considered: integrators turn
/// the normal to the side the ray arrives from).
struct PbrSurface {
    Vec3 baseColor;
    double metallic = 0, roughness = 1, transmission = 0;
    Vec3 emission;
    /// The shading normal, world space, unit: the interpolated normal bent by the normal map.
    Vec3 normal;
    double specular = 1;
    Vec3 specularColor{1};
    double clearcoat = 0, clearcoatRoughness = 0;
    Vec3 clearcoatNormal;  ///< World space, unit.
    Vec3 sheenColor{0};
    double sheenRoughness = 0;
    double anisotropy = 0;
    Vec3 anisotropyDirection;  ///< World space, in the tangent plane; zero without anisotropy.
    double iridescence = 0, iridescenceThickness = 400;
    double diffuseTransmission = 0;
    Vec3 diffuseTransmissionColor{1};
};

/// The material `m` at hit `si`.
PbrSurface evalSurface(const PbrMaterial& m, const SurfaceInteraction& si);
/// Opacity of `m` at hit `si`: alpha of the base colour (factor, texture, vertex colour).
double opacityAt(const PbrMaterial& m, const SurfaceInteraction& si);
/// Emitted radiance of `m` at `si` (emissive factor times texture).
Vec3 emissionAt(const PbrMaterial& m, const SurfaceInteraction& si);

}  // namespace glint
