#pragma once
/// Which glTF extensions Glint renders: the one table that says so. The loader reports every
/// extension a file uses with its entry here (Model::extensions, which `glint --check` lists),
/// warns once for each it ignores (an extension rendered in part is warned of where the file
/// uses what is left out, as a spot light), and refuses a file that requires one it ignores.
/// Changing what Glint supports is editing a line of kGltfExtensions (docs/scene-format.md,
/// "glTF extensions", lists the same).

#include <array>
#include <cstdint>
#include <string>
#include <string_view>

namespace glint {

enum class GltfSupport : uint8_t {
    Rendered,  ///< Read and rendered as its specification defines it.
    Partly,    ///< Read, but the note says what is left out.
    Ignored,   ///< Not read: the note says what the user loses.
    Metadata,  ///< Describes the file, not what it looks like: there is nothing to render.
};

struct GltfExtension {
    std::string_view name;
    GltfSupport support;
    /// For Partly and Ignored: what is left out, in words for the user (after "ignored: ").
    std::string_view note;
};

// clang-format off
/// Every extension Glint knows, by name. An extension not listed is ignored (unknownGltfNote).
inline constexpr std::array kGltfExtensions = {
    GltfExtension{"EXT_meshopt_compression", GltfSupport::Rendered, ""},
    GltfExtension{"KHR_animation_pointer", GltfSupport::Partly,
                  "nodes' transforms and weights, materials' factors, texture transforms and "
                  "extensions' numbers, punctual lights and perspective cameras are played; "
                  "other targets are not, with a warning naming each"},
    GltfExtension{"EXT_mesh_gpu_instancing", GltfSupport::Ignored,
                  "the instances are not placed, only each node's own mesh"},
    GltfExtension{"EXT_texture_avif", GltfSupport::Ignored,
                  "AVIF images are not decoded, so a texture shows its fallback image, or its "
                  "material's factors where it has none"},
    GltfExtension{"EXT_texture_webp", GltfSupport::Rendered, ""},  // not by the web build
    GltfExtension{"KHR_draco_mesh_compression", GltfSupport::Rendered, ""},
    GltfExtension{"KHR_lights_punctual", GltfSupport::Rendered, ""},
    GltfExtension{"KHR_materials_anisotropy", GltfSupport::Rendered, ""},
    GltfExtension{"KHR_materials_clearcoat", GltfSupport::Rendered, ""},
    GltfExtension{"KHR_materials_diffuse_transmission", GltfSupport::Rendered, ""},
    GltfExtension{"KHR_materials_dispersion", GltfSupport::Partly,
                  "the light pass for caustics refracts every colour alike"},
    GltfExtension{"KHR_materials_emissive_strength", GltfSupport::Rendered, ""},
    GltfExtension{"KHR_materials_ior", GltfSupport::Rendered, ""},
    GltfExtension{"KHR_materials_iridescence", GltfSupport::Rendered, ""},
    GltfExtension{"KHR_materials_pbrSpecularGlossiness", GltfSupport::Ignored,
                  "specular-glossiness materials are shaded by their metallic-roughness factors "
                  "(glTF's defaults where the file gives none)"},
    GltfExtension{"KHR_materials_sheen", GltfSupport::Rendered, ""},
    GltfExtension{"KHR_materials_specular", GltfSupport::Rendered, ""},
    GltfExtension{"KHR_materials_transmission", GltfSupport::Rendered, ""},
    GltfExtension{"KHR_materials_unlit", GltfSupport::Rendered, ""},  // seen by the camera only
    GltfExtension{"KHR_materials_variants", GltfSupport::Rendered, ""},  // --variant
    GltfExtension{"KHR_materials_volume", GltfSupport::Rendered, ""},
    GltfExtension{"KHR_materials_volume_scatter", GltfSupport::Rendered, ""},  // a medium
    GltfExtension{"KHR_mesh_quantization", GltfSupport::Rendered, ""},
    GltfExtension{"KHR_meshopt_compression", GltfSupport::Rendered, ""},
    GltfExtension{"KHR_texture_basisu", GltfSupport::Ignored,
                  "KTX2 images are not decoded, so a texture shows its fallback image, or its "
                  "material's factors where it has none"},
    GltfExtension{"KHR_texture_transform", GltfSupport::Rendered, ""},
    GltfExtension{"KHR_xmp", GltfSupport::Metadata, ""},
    GltfExtension{"KHR_xmp_json_ld", GltfSupport::Metadata, ""},
};
// clang-format on

/// What Glint says of an extension the table does not list.
inline constexpr std::string_view kUnknownGltfNote = "Glint does not know this extension";

/// The table's entry for extension `name`, or null if it does not list it.
const GltfExtension* findGltfExtension(std::string_view name);

/// Whether Glint renders extension `name` at least in part (a file may require it).
bool rendersGltfExtension(std::string_view name);

/// What Glint does with extension `name`, for the user: "rendered", "partly: <note>",
/// "ignored: <note>" or "metadata: nothing to render".
std::string gltfSupportText(std::string_view name);

}  // namespace glint
