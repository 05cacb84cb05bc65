#pragma once
/// glTF 2.0 assets (.gltf with external or embedded buffers and images, and binary .glb), read
/// with tinygltf and checked by Glint: the meshes of the default scene's node trees, each placed
/// by its node's world transform (skinned meshes posed by their skins instead), their
/// metallic-roughness materials mapped to Glint's model, a camera (the first perspective one,
/// or the one asked for) and the KHR_lights_punctual lights (docs/scene-format.md, "glTF").
/// The result is a Model (scene/model.h): one glTF mesh is one MeshData, however many nodes
/// place it (Model::meshes is indexed like the file's meshes; a mesh posed by a skin and used
/// otherwise too is posed in a copy appended after them).

#include <memory>
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
    /// Which animation to play, at what time (parseGltf, loadGltf); by default none.
    ModelTime time{};
    /// KHR_materials_variants: the variant, by name or by its number, whose materials the
    /// primitives it maps take; empty: the file's own materials. A file without it, or without
    /// a variant of that name, is an error that lists the variants there are.
    std::string variant;
};

/// Parses the glTF asset `bytes` (JSON text, or a binary .glb recognised by its magic);
/// `fileName` names it in messages, and its directory is where external buffers and images are
/// found. Throws SceneError naming the file at the first error, or if the asset would need more
/// memory than `options.limits` allow; appends warnings.
Model parseGltf(std::string_view bytes, const std::string& fileName,
                std::vector<Diagnostic>& warnings, const GltfOptions& options = {});

/// A glTF asset parsed once and posed at any time of its animations: a sequence of frames
/// reads the file once and decodes each image once (the meshes are read again at each pose).
class GltfDocument {
  public:
    /// Parses `bytes` as parseGltf does, and checks it; nothing is posed yet.
    GltfDocument(std::string_view bytes, const std::string& fileName,
                 std::vector<Diagnostic>& warnings, const GltfOptions& options = {});
    ~GltfDocument();
    GltfDocument(const GltfDocument&) = delete;
    GltfDocument& operator=(const GltfDocument&) = delete;

    /// The file's animations.
    const std::vector<ModelAnimation>& animations() const;
    /// The model at `time` (options.time is not used here), with the options' camera choice.
    /// Appends the warnings not given before by this asset; throws SceneError as parseGltf.
    Model pose(const ModelTime& time, std::vector<Diagnostic>& warnings);

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

/// Reads the glTF file at `path` and parses it into an asset to pose.
std::shared_ptr<GltfDocument> openGltf(const std::string& path, std::vector<Diagnostic>& warnings,
                                       const GltfOptions& options = {});

/// Reads and parses the glTF file at `path`, posed at options.time.
Model loadGltf(const std::string& path, std::vector<Diagnostic>& warnings,
               const GltfOptions& options = {});

}  // namespace glint
