#pragma once
/// glTF 2.0 assets (.gltf with external or embedded buffers and images, and binary .glb), read
/// with tinygltf and checked by Glint: the meshes of the default scene's node trees, each placed
/// by its node's world transform, their metallic-roughness materials mapped to Glint's model,
/// the first perspective camera and the KHR_lights_punctual lights (docs/scene-format.md,
/// "glTF"). Loading and placing are separate, as for OBJ meshes: one glTF mesh is one MeshData,
/// however many nodes place it.

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "glint/core/error.h"
#include "glint/core/input_file.h"
#include "glint/scene/camera.h"
#include "glint/scene/light.h"
#include "glint/scene/mesh.h"
#include "glint/scene/scene_builder.h"

namespace glint {

struct GltfOptions {
    /// Memory, and whether the files a .gltf names (buffers, images) may be read. With
    /// readFiles off only the input's own bytes are used: embedded (data: URI) buffers and
    /// images, and a .glb's binary chunk.
    LoadLimits limits;
};

/// One glTF mesh placed by one node.
struct GltfPlacement {
    uint32_t mesh = 0;          ///< Index into GltfModel::meshes (the glTF mesh index).
    Transform worldFromObject;  ///< The node's world transform: its ancestors' and its own.
    uint32_t node = 0;          ///< The glTF node, for messages.
};

/// The camera a glTF asset's node tree holds first (a perspective camera).
struct GltfCamera {
    CameraSpec spec;          ///< Eye at the node's origin, looking down its -z, up its +y.
    double aspectRatio = 0;   ///< Width / height the camera was made for; 0: not given.
    std::string description;  ///< "camera 0 'Main' (node 3)", for messages.
};

/// A glTF asset in Glint's terms, in the asset's own space (metres, +y up, right-handed, like
/// Glint's world).
struct GltfModel {
    std::string name;  ///< The file it came from.
    /// Indexed like the file's meshes. A mesh no node of the scene places is left empty (it is
    /// not read at all).
    std::vector<MeshData> meshes;
    std::vector<GltfPlacement> placements;  ///< In node order, depth first.
    std::optional<GltfCamera> camera;
    std::vector<Light> lights;  ///< KHR_lights_punctual lights, placed by their nodes.

    size_t triangles() const;  ///< Triangles placed by all placements together.
};

/// Glint's light colour for a glTF light of `intensity` (candela for point lights, lux for
/// directional ones): colour x intensity / pi, so that a white Lambertian surface lit head-on
/// shows the radiance a physically based glTF viewer computes, before its exposure.
constexpr double kGltfLightScale = 0.31830988618379067;  // 1 / pi

/// Parses the glTF asset `bytes` (JSON text, or a binary .glb recognised by its magic);
/// `fileName` names it in messages, and its directory is where external buffers and images are
/// found. Throws SceneError naming the file at the first error, or if the asset would need more
/// memory than `options.limits` allow; appends warnings.
GltfModel parseGltf(std::string_view bytes, const std::string& fileName,
                    std::vector<Diagnostic>& warnings, const GltfOptions& options = {});

/// Reads and parses the glTF file at `path`.
GltfModel loadGltf(const std::string& path, std::vector<Diagnostic>& warnings,
                   const GltfOptions& options = {});

/// Whether `path`'s extension is .gltf or .glb (any case).
bool isGltfFile(const std::string& path);

/// Hands every placement of `model` to `builder` under `worldFromModel` (the scene's transform
/// of the whole asset): a glTF mesh that several nodes place is then stored once and instanced.
/// Triangles without a glTF material take `defaultMaterial`; `where` and `what` prefix errors
/// about the placements (MeshPlacer::add). Throws SceneError if a composed transform is
/// singular. `model` must live until the builder has finished.
void placeGltf(SceneBuilder& builder, const GltfModel& model, const Transform& worldFromModel,
               uint32_t defaultMaterial, const FileLoc& where = {}, const std::string& what = {});

}  // namespace glint
