#pragma once
/// glTF 2.0 assets (.gltf with external or embedded buffers and images, and binary .glb), read
/// with tinygltf and checked by Glint: the meshes of the default scene's node trees, each placed
/// by its node's world transform (skinned meshes posed by their skins instead), their
/// metallic-roughness materials mapped to Glint's model, a camera (the first perspective one,
/// or the one asked for) and the KHR_lights_punctual lights (docs/scene-format.md, "glTF").
/// The result is a Model (scene/model.h): one glTF mesh is one MeshData, however many nodes
/// place it (Model::meshes is indexed like the file's meshes; a mesh posed by a skin and used
/// otherwise too is posed in a copy appended after them).

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "glint/core/error.h"
#include "glint/core/input_file.h"
#include "glint/scene/model.h"

namespace glint {

struct GltfOptions {
    /// Memory, and whether the files a .gltf names (buffers, images) may be read. With
    /// readFiles off only the input's own bytes are used: embedded (data: URI) buffers and
    /// images, and a .glb's binary chunk.
    LoadLimits limits;
    /// Which of the file's cameras becomes the model's (Model::camera): by default the first
    /// perspective camera. The cameras are numbered in the order the node walk meets their
    /// nodes: depth first through the default scene's trees, children in order.
    CameraChoice camera;
    /// CPU seconds libdraco may take for the file's Draco meshes together, beyond 20 us per
    /// index decoded: corrupt Draco data can make it spin (docs/robustness.md).
    double dracoSeconds = 2;
};

/// Glint's light colour for a glTF light of `intensity` (candela for point lights, lux for
/// directional ones): colour x intensity / pi, so that a white Lambertian surface lit head-on
/// shows the radiance a physically based glTF viewer computes, before its exposure.
constexpr double kGltfLightScale = 0.31830988618379067;  // 1 / pi

/// Parses the glTF asset `bytes` (JSON text, or a binary .glb recognised by its magic);
/// `fileName` names it in messages, and its directory is where external buffers and images are
/// found. Throws SceneError naming the file at the first error, or if the asset would need more
/// memory than `options.limits` allow; appends warnings.
Model parseGltf(std::string_view bytes, const std::string& fileName,
                std::vector<Diagnostic>& warnings, const GltfOptions& options = {});

/// Reads and parses the glTF file at `path`.
Model loadGltf(const std::string& path, std::vector<Diagnostic>& warnings,
               const GltfOptions& options = {});

}  // namespace glint
