#pragma once
// Shared by gltf_loader.cpp (the file, node trees, cameras, lights), gltf_meshes.cpp
// (accessors and meshes), gltf_materials.cpp (materials and their images) and
// gltf_compression.cpp (compressed meshes). Internal to glint/io: use gltf_loader.h.

#include <bit>
#include <map>
#include <memory>
#include <nlohmann/json_fwd.hpp>
#include <optional>
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

struct Compression;  // gltf_compression.cpp

/// What loading one asset shares: the file, tinygltf's model of it, and the warnings.
struct Context {
    Context(const std::string& file, std::vector<Diagnostic>& warnings, const GltfOptions& options);

    const std::string& file;
    std::string dir;  ///< Where its external buffers and images are ("" for the current one).
    std::vector<Diagnostic>& warnings;
    const GltfOptions& options;
    tinygltf::Model model;
    size_t externalBytes = 0;  ///< Read from external buffer files so far.
    /// What the compression extensions need (gltf_compression.cpp): null when the file uses
    /// none. Its decoded data is made when first asked for, through a const Context too.
    std::shared_ptr<Compression> compression;

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

// Compressed meshes (gltf_compression.cpp): KHR_draco_mesh_compression through libdraco,
// EXT_meshopt_compression and KHR_meshopt_compression through libmeshoptimizer.

/// Whether JSON text may use a compression extension (a look at its text: false means it does
/// not; true that prepareCompression() must see the parsed JSON).
bool mayUseCompression(std::string_view json);
/// Prepares the parsed JSON `j` for tinygltf, which (as Debian builds it, without Draco) cannot
/// read compressed files: takes the `indices` of Draco primitives out (their accessors have no
/// bufferView, which tinygltf rejects) and replaces meshopt fallback buffers (which may have
/// no data) by a byte, after checking the extensions' objects. What it takes and what the
/// decoders need go to ctx.compression. Returns whether `j` changed. `glb`: the JSON of a .glb.
bool prepareCompression(Context& ctx, nlohmann::json& j, bool glb);
/// After tinygltf's parse: puts the Draco primitives' indices back, and finds which accessors
/// Draco primitives decode.
void restoreCompression(Context& ctx);
/// The elements of accessor `index` decoded from its KHR_draco_mesh_compression primitive, laid
/// out tightly as the accessor declares them (type, component type, count); null if no Draco
/// primitive holds the accessor. The primitive is decoded when first asked for.
const std::vector<unsigned char>* dracoAccessor(const Context& ctx, int index);
/// The decoded bytes of bufferView `index` (in range) if it is meshopt-compressed (its
/// byteLength), decoded when first asked for; nullopt if it is not compressed.
std::optional<std::string_view> meshoptBufferView(const Context& ctx, int index);
/// Bytes the decoders hold (for memory estimates).
size_t decompressedBytes(const Context& ctx);

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
