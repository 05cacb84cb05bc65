#pragma once
// Shared by gltf_loader.cpp (the file, node trees, cameras, lights), gltf_meshes.cpp
// (accessors and meshes) and gltf_materials.cpp (materials and their images). Internal to
// glint/io: use gltf_loader.h.

#include <bit>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "glint/core/error.h"
#include "glint/io/gltf/gltf_loader.h"
#include "glint/io/gltf/tinygltf.h"
#include "glint/scene/mesh.h"

namespace glint::gltf {

static_assert(std::endian::native == std::endian::little,
              "glTF's binary data is little-endian, and Glint reads it as it lies");

/// What loading one asset shares: the file, tinygltf's model of it, and the warnings.
struct Context {
    Context(const std::string& file, std::vector<Diagnostic>& warnings, const GltfOptions& options);

    const std::string& file;
    std::string dir;  ///< Where its external buffers and images are ("" for the current one).
    std::vector<Diagnostic>& warnings;
    const GltfOptions& options;
    tinygltf::Model model;
    size_t externalBytes = 0;  ///< Read from external buffer files so far.

    /// Throws SceneError naming the file.
    [[noreturn]] void fail(const std::string& message) const;
    void warn(const std::string& message);
    /// Warns once per `key` for the whole file, adding " (reported once)".
    void warnOnce(const std::string& key, const std::string& message);

  private:
    std::set<std::string> warned_;
};

/// Parses the file's bytes (JSON text or a .glb) with tinygltf into ctx.model, after checking
/// what tinygltf would not check first (gltf_container.cpp).
void parseContainer(Context& ctx, std::string_view bytes);
/// Checks the asset's version and the extensions it requires; warns of what Glint ignores.
void checkAsset(Context& ctx);

/// "mesh 2 'Cube'", "node 0", ...: an object of the file with its name, for messages.
std::string describe(const char* kind, size_t index, const std::string& name);

/// "texture 5 does not exist (the file has 2 textures)": for references out of range.
[[noreturn]] void missing(const Context& ctx, const char* kind, long long index, size_t count,
                          const std::string& user);

/// The bytes of bufferView `index`, checked to lie in its buffer. `user` names who refers to
/// it, for messages.
std::string_view bufferViewBytes(const Context& ctx, int index, const std::string& user);

/// Counts of a mesh, for the memory estimate: an upper bound of what readMesh() stores.
struct MeshCounts {
    size_t positions = 0, normals = 0, uvs = 0, triangles = 0;
    size_t normalTriangles = 0, uvTriangles = 0;  ///< Triangles with normals, with uvs.
};

/// Checks every primitive of glTF mesh `mesh` (modes, attribute and index accessors and their
/// byte ranges) without reading its data, and counts what it holds.
MeshCounts countMesh(Context& ctx, int mesh);

/// Glint's materials for the file's glTF materials, each mapped once, with their images.
class Materials {
  public:
    explicit Materials(Context& ctx) : ctx_(ctx) {}
    /// Glint's material for glTF material `index` (in range).
    const MeshMaterial& get(int index);

  private:
    MeshMaterial map(int index);
    /// A texture slot of a material (image, sampler, coordinate set, KHR_texture_transform);
    /// empty (with a warning) if it has no image Glint can use.
    TextureSlot slot(int texture, int texCoord, const tinygltf::ExtensionMap& extensions,
                     const std::string& material, const char* slot, bool srgb, const char* instead);
    std::shared_ptr<const TextureImage> image(int index, bool srgb, std::string& problem);

    Context& ctx_;
    std::map<int, MeshMaterial> mapped_;
    struct Decoded {
        std::shared_ptr<const TextureImage> image;
        std::string problem;  ///< Why there is none.
    };
    std::map<std::pair<int, bool>, Decoded> images_;  ///< By (image, sRGB).
};

/// Reads glTF mesh `mesh` (checked by countMesh) into a MeshData: its primitives' triangles,
/// with positions, normals and texture coordinates, and their materials through `materials`.
/// `counts` (from countMesh) reserves the storage.
MeshData readMesh(Context& ctx, int mesh, const MeshCounts& counts, Materials& materials);

}  // namespace glint::gltf
