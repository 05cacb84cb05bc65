#pragma once
// What the compressed-mesh code shares: gltf_compression.cpp (the JSON prepared for tinygltf,
// the extensions' objects, meshopt) and gltf_draco.cpp (Draco). Internal to glint/io/gltf: the
// rest of the loader calls the functions gltf_internal.h declares.

#include <cstddef>
#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "glint/io/gltf/gltf_internal.h"

namespace glint::gltf {

inline constexpr const char* kDraco = "KHR_draco_mesh_compression";
inline constexpr const char* kMeshoptExt = "EXT_meshopt_compression";
inline constexpr const char* kMeshoptKhr = "KHR_meshopt_compression";

enum class MeshoptMode { Attributes, Triangles, Indices };
enum class MeshoptFilter { None, Octahedral, Quaternion, Exponential, Color };

/// A bufferView's meshopt extension, as the JSON gives it.
struct MeshoptView {
    const char* extension = kMeshoptExt;
    size_t buffer = 0, byteOffset = 0, byteLength = 0, byteStride = 0, count = 0;
    MeshoptMode mode = MeshoptMode::Attributes;
    MeshoptFilter filter = MeshoptFilter::None;
};

/// A primitive's KHR_draco_mesh_compression, as the JSON gives it.
struct DracoPrimitive {
    size_t mesh = 0, primitive = 0, bufferView = 0;
    std::vector<std::pair<std::string, uint32_t>> attributes;  ///< glTF name, Draco unique id
    bool decoded = false;
};

/// Where a Draco primitive's accessor comes from: its faces, or an attribute's unique id.
struct DracoSource {
    size_t primitive = 0;  ///< In Compression::draco.
    bool indices = false;
    uint32_t uniqueId = 0;
};

/// What loading one asset needs for its compressed data (Context::compression): what the JSON
/// says, what was taken from it for tinygltf, and what is decoded so far.
struct Compression {
    std::map<std::pair<size_t, size_t>, int> removedIndices;  ///< (mesh, primitive): indices
    std::vector<DracoPrimitive> draco;
    std::map<int, DracoSource> dracoAccessors;            ///< by accessor
    std::map<int, std::vector<unsigned char>> accessors;  ///< decoded, by accessor
    std::map<size_t, MeshoptView> meshopt;                ///< by bufferView
    std::map<size_t, std::vector<unsigned char>> views;   ///< decoded, by bufferView
    std::set<size_t> placeholders;  ///< fallback buffers replaced by a byte for tinygltf
    size_t bytes = 0;               ///< decoded so far
    double dracoSeconds = 0;        ///< CPU time in libdraco so far
    double dracoIndices = 0;        ///< indices (3 per triangle) libdraco has decoded so far
};

/// "mesh 0 'Cube', primitive 1: KHR_draco_mesh_compression"
std::string dracoLabel(const Context& ctx, const DracoPrimitive& d);

/// Fails, naming `what`, unless `more` bytes of decoded data fit in the memory available with
/// what is decoded already.
void reserveDecoded(const Context& ctx, const Compression& c, double more, const std::string& what);

/// Decodes Draco primitive `which` (of c.draco) with libdraco into the accessors it holds
/// (c.accessors), checked against the decoded mesh (gltf_draco.cpp).
void decodeDraco(const Context& ctx, Compression& c, size_t which);

/// Decodes the meshopt data of `m` (`source`, m.byteLength bytes, checked against the
/// extension's rules) into `out`, sized for `count` elements of `stride` bytes, and applies its
/// filter; fails through `ctx`, naming `label`, when the data is corrupt (gltf_meshopt.cpp).
void decodeMeshoptData(const Context& ctx, const MeshoptView& m, const std::string& label,
                       const unsigned char* source, size_t count, size_t stride,
                       std::vector<unsigned char>& out);

}  // namespace glint::gltf
