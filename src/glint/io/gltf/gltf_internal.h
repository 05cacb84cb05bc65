#pragma once
// Shared by gltf_loader.cpp (the file, node trees, cameras, lights), gltf_meshes.cpp
// (accessors and meshes), gltf_skins.cpp (skinned meshes posed), gltf_materials.cpp
// (materials and their images) and gltf_compression.cpp (compressed meshes). Internal to
// glint/io: use gltf_loader.h.

#include <array>
#include <bit>
#include <cstdint>
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
#include "glint/math/mat4.h"
#include "glint/scene/mesh.h"
#include "glint/scene/model.h"

namespace glint::gltf {

static_assert(std::endian::native == std::endian::little,
              "glTF's binary data is little-endian, and Glint reads it as it lies");

struct Compression;  // gltf_compression.cpp

/// The values an animation gives one node at the time posed (gltf_animations.cpp): each
/// replaces the node's own.
struct AnimatedNode {
    std::optional<std::array<double, 3>> translation, scale;
    std::optional<std::array<double, 4>> rotation;  ///< A unit quaternion x, y, z, w.
    std::optional<std::vector<double>> weights;     ///< Morph target weights.
};

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
    /// By node, what the animation played gives it; empty when none is played.
    std::vector<AnimatedNode> animated;
    /// KHR_animation_pointer: each property the animation played set in `model` (a JSON
    /// pointer) with the value it had before, to be put back before the next pose; and the
    /// materials it changed, to be mapped again.
    std::vector<std::pair<std::string, std::vector<double>>> pointed;
    std::set<int> pointedMaterials;

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

/// Every extension the file uses (extensionsUsed, extensionsRequired, and those found on its
/// objects), by name, with what Glint does with each (gltf_extensions.h); warns once for each
/// that Glint ignores. KHR_materials_variants' entry lists the variants and says which is shown
/// (`variant`, as GltfOptions::variant).
std::vector<FormatExtension> reportExtensions(Context& ctx, const std::string& variant = "");

/// The names of the file's material variants (KHR_materials_variants), in order ("variant N"
/// for one without a name); empty if it has none.
std::vector<std::string> materialVariants(const Context& ctx);
/// Gives each primitive that KHR_materials_variants maps for `variant` (a name, or a number
/// from 0) that variant's material; nothing for an empty `variant`. Fails if the file has no
/// such variant, listing those it has.
void applyVariant(Context& ctx, const std::string& variant);

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
    size_t uv1s = 0, colors = 0, tangents = 0;    ///< Read from the file.
    size_t generatedTangents = 0;  ///< At most, for primitives with a normal map and no TANGENT.
    size_t largestGeneration = 0;  ///< Triangles of the largest such primitive.
    size_t extraTriangles = 0;     ///< Triangles with TEXCOORD_1, COLOR_0 or tangents.

    /// Bytes of the MeshData.
    double bytes() const;
};

/// Checks every primitive of glTF mesh `mesh` (modes, attribute and index accessors and their
/// byte ranges) without reading its data, and counts what it holds.
MeshCounts countMesh(Context& ctx, int mesh);

/// Glint's materials for the file's glTF materials, each mapped once, with their images.
/// A number of a glTF extension object, `fallback` when absent. Present but not a finite
/// number is an error.
double extensionNumber(const Context& ctx, const tinygltf::ExtensionMap& extensions,
                       const char* extension, const char* key, double fallback,
                       const std::string& label);

class Materials {
  public:
    explicit Materials(Context& ctx) : ctx_(ctx) {}
    /// Glint's material for glTF material `index` (in range).
    const MeshMaterial& get(int index);
    /// Forgets the mapping of material `index`: its values changed (an animation pointer).
    void forget(int index) { mapped_.erase(index); }

  private:
    MeshMaterial map(int index);
    /// A texture slot of a material (image, sampler, coordinate set, KHR_texture_transform);
    /// empty (with a warning) if it has no image Glint can use.
    TextureSlot slot(int texture, int texCoord, const tinygltf::ExtensionMap& extensions,
                     const std::string& material, const char* slot, bool srgb, const char* instead);
    std::shared_ptr<const TextureImage> image(int index, bool srgb, std::string& problem);
    /// The texture `key` of extension object `ext` (a textureInfo: index, texCoord and its own
    /// extensions); empty when absent.
    TextureSlot extensionSlot(const tinygltf::Value& ext, const char* key,
                              const std::string& material, bool srgb, const char* instead);
    /// The layers of the material extensions (clearcoat, sheen, specular, anisotropy,
    /// iridescence, diffuse transmission) into `p` (gltf_material_layers.cpp).
    void mapLayers(const tinygltf::Material& m, PbrMaterial& p, const std::string& label);
    /// The colour `key` of extension object `ext` (three finite numbers, clamped to [0, most]),
    /// `fallback` where it has none; fails, naming `material`, for anything else.
    Vec3 extensionColour(const tinygltf::Value& ext, const char* key, Vec3 fallback, double most,
                         const std::string& material) const;

    Context& ctx_;
    std::map<int, MeshMaterial> mapped_;
    struct Decoded {
        std::shared_ptr<const TextureImage> image;
        std::string problem;  ///< Why there is none.
    };
    std::map<std::pair<int, bool>, Decoded> images_;  ///< By (image, sRGB).
};

/// The joints and weights of a mesh's vertices (JOINTS_0/WEIGHTS_0, and _1), by MeshData
/// position: up to kInfluences per vertex, weights as the file has them (0 where it has none).
struct VertexWeights {
    static constexpr size_t kInfluences = 8;
    struct Vertex {
        std::array<uint16_t, kInfluences> joints{};
        std::array<float, kInfluences> weights{};
        bool operator==(const Vertex&) const = default;
    };
    std::vector<Vertex> vertices;
};

/// The number of morph targets of glTF mesh `mesh` (in range), checked: every primitive has as
/// many, and the mesh's `weights`, when present, has one finite number per target.
size_t morphTargetCount(const Context& ctx, int mesh);

/// Reads glTF mesh `mesh` (checked by countMesh) into a MeshData: its primitives' triangles,
/// with positions, normals, texture coordinates (both sets), colours and tangents (generated,
/// MikkTSpace-compatibly, for primitives whose material has a normal map and that have no
/// TANGENT), and their materials through `materials`. `counts` (from countMesh) reserves the
/// storage. With `weights`, also reads the joints and weights of its vertices for skinning.
/// Positions, normals and tangents are morphed by its morph targets with `morphWeights` (one
/// finite weight per target, as morphTargetCount() counts them); null: the mesh's own
/// `weights`, or zeros (its base shape) when it has none.
MeshData readMesh(Context& ctx, int mesh, const MeshCounts& counts, Materials& materials,
                  VertexWeights* weights = nullptr,
                  const std::vector<double>* morphWeights = nullptr);

/// The matrices (MAT4, column-major in the file) of accessor `index`, at least `count` of them;
/// `user` names who refers to it, for messages.
std::vector<Mat4> readMatrices(const Context& ctx, int index, size_t count,
                               const std::string& user);

/// Node `node`'s transform relative to its parent: its matrix, or translation x rotation x
/// scale, each as the animation played gives it (ctx.animated) or as the node holds it.
/// `label` names the node in messages.
Mat4 localMatrix(const Context& ctx, size_t node, const std::string& label);

/// The elements of an accessor as floats, normalised integers mapped to [0, 1] or [-1, 1].
struct FloatElements {
    std::vector<float> values;  ///< count x components
    size_t count = 0, components = 0;
    std::string label;  ///< "accessor 7 (input of animation 0, sampler 2)"
};

/// Reads accessor `index` (`user` refers to it, for messages), which must hold floats, or
/// normalised integers when `normalised` (animation outputs of rotations and weights may).
/// Every value must be finite.
FloatElements readFloats(const Context& ctx, int index, const std::string& user, bool normalised);

// Animations (gltf_animations.cpp).

/// The file's animations, for the user: names, channel counts and the range of their key
/// times (from the input accessors' min and max, which glTF requires, else read).
std::vector<ModelAnimation> listAnimations(const Context& ctx);

/// Plays the animation `time` chooses at its time into ctx.animated; returns its index, and
/// says what was played in `played` ("animation 0 'Walk' at 1.25 s"). A file without
/// animations stays still (none is returned) unless one is named. Throws SceneError, naming the
/// animation and its sampler or channel, for data that cannot be played: a missing animation (the
/// message lists them), key times not increasing, counts that disagree, values not finite.
std::optional<size_t> playAnimation(Context& ctx, const ModelTime& time, std::string& played);
/// Puts back what the last animation played through KHR_animation_pointer changed in ctx.model.
void unplayPointers(Context& ctx);

/// A node placing a mesh with a skin: its placement is posed by the skin (gltf_skins.cpp).
struct SkinnedPlacement {
    size_t placement = 0;  ///< Index in Model::placements.
    int skin = -1, node = -1;
    Mat4 nodeWorld;  ///< The node's world transform: for vertices without weights.
};

/// Poses every skinned placement: each vertex v' = sum_i w_i (world(joint_i) x
/// inverseBind_i) v (the glTF specification's skinning, in the pose the nodes' own transforms
/// give), normals by the inverse transpose of that matrix and tangents by the matrix. A mesh
/// posed by one skin and placed by no other node is posed where it is; otherwise each (mesh,
/// skin) is a copy appended to `out.meshes`. `weights` holds, by mesh, the weights readMesh()
/// read (for each mesh a skinned placement uses). The placements then have the identity.
void poseSkins(Context& ctx, Model& out, const std::vector<SkinnedPlacement>& skinned,
               std::vector<VertexWeights>& weights);

}  // namespace glint::gltf
