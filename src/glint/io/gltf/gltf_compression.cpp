// Compressed glTF meshes: KHR_draco_mesh_compression through libdraco 1.5.5 (gltf_draco.cpp), and
// EXT_meshopt_compression and KHR_meshopt_compression (its version-0 streams) through
// libmeshoptimizer 0.18 (gltf_meshopt.cpp), the Debian 12 packages (docs/scene-format.md,
// "Compressed meshes").
//
// tinygltf 2.7 as Debian builds it has no Draco, and cannot read either extension's files: it
// rejects a primitive whose indices accessor has no bufferView (Draco's accessors have none),
// and a buffer with neither a URI nor the .glb's chunk (meshopt's fallback buffers). So the JSON
// is prepared before tinygltf reads it (prepareCompression), and put back after
// (restoreCompression). Decoding happens when an accessor or bufferView is first read, into
// memory the Context owns: a Draco primitive's accessors are filled in the layout they declare,
// and a meshopt bufferView holds the bytes its uncompressed fallback would have held, so that
// accessor reading (gltf_meshes.cpp) works on them as on any other.

#include "glint/io/gltf/gltf_compression.h"

#include <algorithm>
#include <limits>
#include <nlohmann/json.hpp>

#include "glint/core/system.h"

namespace glint::gltf {
namespace {

/// What stands in for a meshopt fallback buffer for tinygltf: one byte (tinygltf refuses an
/// empty data: URI).
constexpr const char* kPlaceholderUri = "data:application/octet-stream;base64,AA==";

using json = nlohmann::json;

const json* member(const json& o, const char* key) {
    if (!o.is_object()) return nullptr;
    auto it = o.find(key);
    return it == o.end() ? nullptr : &*it;
}

const json* extension(const json& o, const char* name) {
    const json* e = member(o, "extensions");
    return e ? member(*e, name) : nullptr;
}

/// Member `key` of `o` as a count or index: a non-negative integer (`fallback` when absent and
/// allowed, else an error naming `what`).
size_t unsignedMember(const Context& ctx, const json& o, const char* key, const std::string& what,
                      std::optional<size_t> fallback = std::nullopt) {
    const json* v = member(o, key);
    if (!v) {
        if (fallback) return *fallback;
        ctx.fail(what + ": '" + key + "' is required");
    }
    if (!v->is_number_unsigned()) ctx.fail(what + ": '" + key + "' must be an integer, 0 or more");
    const uint64_t x = v->get<uint64_t>();
    if (x > std::numeric_limits<uint32_t>::max())
        ctx.fail(what + ": '" + key + "' is " + std::to_string(x) + ", beyond what Glint reads");
    return static_cast<size_t>(x);
}

std::string stringMember(const Context& ctx, const json& o, const char* key,
                         const std::string& what, const char* fallback = nullptr) {
    const json* v = member(o, key);
    if (!v) {
        if (fallback) return fallback;
        ctx.fail(what + ": '" + key + "' is required");
    }
    if (!v->is_string()) ctx.fail(what + ": '" + key + "' must be a string");
    return v->get<std::string>();
}

MeshoptView parseMeshopt(const Context& ctx, const json& e, const char* name,
                         const std::string& view) {
    const std::string what = view + ": " + name;
    if (!e.is_object()) ctx.fail(what + " must be an object");
    MeshoptView m;
    m.extension = name;
    m.buffer = unsignedMember(ctx, e, "buffer", what);
    m.byteOffset = unsignedMember(ctx, e, "byteOffset", what, 0);
    m.byteLength = unsignedMember(ctx, e, "byteLength", what);
    m.byteStride = unsignedMember(ctx, e, "byteStride", what);
    m.count = unsignedMember(ctx, e, "count", what);
    const std::string mode = stringMember(ctx, e, "mode", what);
    if (mode == "ATTRIBUTES")
        m.mode = MeshoptMode::Attributes;
    else if (mode == "TRIANGLES")
        m.mode = MeshoptMode::Triangles;
    else if (mode == "INDICES")
        m.mode = MeshoptMode::Indices;
    else
        ctx.fail(what + ": mode '" + mode + "' is not ATTRIBUTES, TRIANGLES or INDICES");
    const bool khr = std::string_view(name) == kMeshoptKhr;
    const std::string filter = stringMember(ctx, e, "filter", what, "NONE");
    if (filter == "NONE")
        m.filter = MeshoptFilter::None;
    else if (filter == "OCTAHEDRAL")
        m.filter = MeshoptFilter::Octahedral;
    else if (filter == "QUATERNION")
        m.filter = MeshoptFilter::Quaternion;
    else if (filter == "EXPONENTIAL")
        m.filter = MeshoptFilter::Exponential;
    else if (filter == "COLOR" && khr)
        m.filter = MeshoptFilter::Color;
    else
        ctx.fail(what + ": filter '" + filter + "' is not NONE, OCTAHEDRAL, QUATERNION" +
                 (khr ? ", EXPONENTIAL or COLOR" : " or EXPONENTIAL"));
    return m;
}

DracoPrimitive parseDraco(const Context& ctx, const json& e, size_t mesh, size_t primitive) {
    const std::string what =
        "mesh " + std::to_string(mesh) + ", primitive " + std::to_string(primitive) + ": " + kDraco;
    if (!e.is_object()) ctx.fail(what + " must be an object");
    DracoPrimitive d;
    d.mesh = mesh;
    d.primitive = primitive;
    d.bufferView = unsignedMember(ctx, e, "bufferView", what);
    const json* attributes = member(e, "attributes");
    if (!attributes || !attributes->is_object())
        ctx.fail(what + ": 'attributes' (an object of attribute ids) is required");
    for (auto it = attributes->begin(); it != attributes->end(); ++it)
        d.attributes.emplace_back(
            it.key(), static_cast<uint32_t>(unsignedMember(ctx, *attributes, it.key().c_str(),
                                                           what + " attributes")));
    return d;
}

// ---- meshopt ----

/// Decodes meshopt bufferView `index` described by `m`.
std::vector<unsigned char> decodeMeshopt(const Context& ctx, Compression& c, size_t index,
                                         const MeshoptView& m) {
    const std::string label = "bufferView " + std::to_string(index) + ": " + m.extension;
    const tinygltf::BufferView& bv = ctx.model.bufferViews[index];
    const size_t stride = m.byteStride, count = m.count;
    // The extension's rules (its specification's list), which libmeshoptimizer asserts.
    auto require = [&](bool ok, const std::string& rule) {
        if (!ok) ctx.fail(label + ": " + rule);
    };
    if (m.mode == MeshoptMode::Attributes) {
        require(stride >= 4 && stride <= 256 && stride % 4 == 0,
                "byteStride must be a multiple of 4 from 4 to 256 for ATTRIBUTES, not " +
                    std::to_string(stride));
    } else {
        require(stride == 2 || stride == 4, "byteStride must be 2 or 4 for TRIANGLES and INDICES");
        require(m.filter == MeshoptFilter::None, "TRIANGLES and INDICES take no filter");
        require(m.mode != MeshoptMode::Triangles || count % 3 == 0,
                "count must be a multiple of 3 for TRIANGLES, not " + std::to_string(count));
    }
    if (m.filter == MeshoptFilter::Octahedral)
        require(stride == 4 || stride == 8, "byteStride must be 4 or 8 for OCTAHEDRAL");
    if (m.filter == MeshoptFilter::Quaternion)
        require(stride == 8, "byteStride must be 8 for QUATERNION");
    if (m.filter == MeshoptFilter::Color)
        ctx.fail(label +
                 ": filter COLOR is not supported: Debian 12's libmeshoptimizer 0.18 "
                 "predates it");
    require(bv.byteStride == 0 || bv.byteStride == stride, "byteStride " + std::to_string(stride) +
                                                               " differs from the bufferView's (" +
                                                               std::to_string(bv.byteStride) + ")");
    require(bv.byteLength / stride == count && bv.byteLength % stride == 0,
            "count x byteStride (" + std::to_string(count) + " x " + std::to_string(stride) +
                ") must be the bufferView's byteLength (" + std::to_string(bv.byteLength) + ")");

    const auto& buffers = ctx.model.buffers;
    if (m.buffer >= buffers.size())
        missing(ctx, "buffer", static_cast<long long>(m.buffer), buffers.size(), label);
    if (c.placeholders.count(m.buffer))
        ctx.fail(label + ": its compressed data is in buffer " + std::to_string(m.buffer) +
                 ", a fallback buffer, which holds none");
    const std::vector<unsigned char>& data = buffers[m.buffer].data;
    if (m.byteOffset > data.size() || m.byteLength > data.size() - m.byteOffset)
        ctx.fail(label + ": its " + std::to_string(m.byteLength) + " bytes from offset " +
                 std::to_string(m.byteOffset) + " lie beyond the end of buffer " +
                 std::to_string(m.buffer) + " (" + std::to_string(data.size()) + " bytes)");
    const unsigned char* source = data.data() + m.byteOffset;
    // What the codecs can make of so many bytes at most (each stores at least 2 bits per 16
    // bytes of attributes, a byte per triangle, a byte per index): a count beyond it is refused
    // before its memory is taken.
    const size_t most = m.mode == MeshoptMode::Attributes  ? m.byteLength * 64
                        : m.mode == MeshoptMode::Triangles ? m.byteLength * 3 * stride
                                                           : m.byteLength * stride;
    if (bv.byteLength > most)
        ctx.fail(label + ": its " + std::to_string(m.byteLength) +
                 " compressed bytes cannot hold " + std::to_string(count) + " elements of " +
                 std::to_string(stride) + " bytes");
    reserveDecoded(ctx, c, double(bv.byteLength), label);

    std::vector<unsigned char> out(bv.byteLength);
    decodeMeshoptData(ctx, m, label, source, count, stride, out);
    return out;
}

}  // namespace

std::string dracoLabel(const Context& ctx, const DracoPrimitive& d) {
    return describe("mesh", d.mesh, ctx.model.meshes[d.mesh].name) + ", primitive " +
           std::to_string(d.primitive) + ": " + kDraco;
}

void reserveDecoded(const Context& ctx, const Compression& c, double more,
                    const std::string& what) {
    const size_t available = memoryAvailable(ctx.options.limits);
    if (available > 0 && double(c.bytes) + more > double(available))
        ctx.fail(what + ": decoding it needs about " + formatBytes(double(c.bytes) + more) +
                 " of memory, more than the " + formatBytes(double(available)) + " available");
}

bool mayUseCompression(std::string_view json) {
    return json.find("_draco_mesh_compression") != std::string_view::npos ||
           json.find("_meshopt_compression") != std::string_view::npos;
}

bool prepareCompression(Context& ctx, json& j, bool glb) {
    if (!j.is_object()) return false;
    auto c = std::make_shared<Compression>();
    bool changed = false;

    // Draco primitives: their extension, and their indices out of tinygltf's sight.
    if (const json* meshes = member(j, "meshes"); meshes && meshes->is_array())
        for (size_t m = 0; m < meshes->size(); ++m) {
            json& mesh = j["meshes"][m];
            if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array())
                continue;
            json& primitives = mesh["primitives"];
            for (size_t k = 0; k < primitives.size(); ++k) {
                json& p = primitives[k];
                const json* e = extension(p, kDraco);
                if (!e) continue;
                c->draco.push_back(parseDraco(ctx, *e, m, k));
                auto indices = p.find("indices");
                if (indices == p.end() || !indices->is_number_integer()) continue;
                const int64_t i = indices->get<int64_t>();  // out of range: "does not exist"
                c->removedIndices[{m, k}] = static_cast<int>(std::clamp<int64_t>(
                    i, std::numeric_limits<int>::min(), std::numeric_limits<int>::max()));
                p.erase(indices);
                changed = true;
            }
        }

    // Meshopt bufferViews, and the buffers they use.
    const json* views = member(j, "bufferViews");
    std::vector<size_t> viewBuffer;      // each view's buffer (SIZE_MAX: none)
    std::map<size_t, size_t> plainUser;  // buffer: a view without meshopt that uses it
    std::set<size_t> compressedUsers;    // buffers used by meshopt views
    if (views && views->is_array())
        for (size_t v = 0; v < views->size(); ++v) {
            const json& view = (*views)[v];
            const json* b = member(view, "buffer");
            const size_t buffer = b && b->is_number_unsigned() ? b->get<size_t>()
                                                               : std::numeric_limits<size_t>::max();
            const json* ext = extension(view, kMeshoptExt);
            const json* khr = extension(view, kMeshoptKhr);
            const std::string label = "bufferView " + std::to_string(v);
            if (ext && khr)
                ctx.fail(label + ": " + kMeshoptExt + " and " + kMeshoptKhr +
                         " exclude each other");
            if (ext || khr) {
                c->meshopt[v] =
                    parseMeshopt(ctx, ext ? *ext : *khr, ext ? kMeshoptExt : kMeshoptKhr, label);
                compressedUsers.insert(buffer);
            } else {
                plainUser.emplace(buffer, v);
            }
        }
    if (json* buffers = j.contains("buffers") ? &j["buffers"] : nullptr;
        buffers && buffers->is_array())
        for (size_t b = 0; b < buffers->size(); ++b) {
            json& buffer = (*buffers)[b];
            if (!buffer.is_object()) continue;
            bool fallback = false;
            for (const char* name : {kMeshoptExt, kMeshoptKhr})
                if (const json* e = extension(buffer, name))
                    if (const json* f = member(*e, "fallback"); f && f->is_boolean())
                        fallback = fallback || f->get<bool>();
            // A buffer with no data of its own that only meshopt views use is a placeholder too
            // (the extension allows it without the flag); in a .glb, buffer 0 is the chunk.
            const bool placeholder = fallback || (!buffer.contains("uri") && (!glb || b > 0) &&
                                                  compressedUsers.count(b) && !plainUser.count(b));
            if (!placeholder) continue;
            if (auto user = plainUser.find(b); user != plainUser.end())
                ctx.fail("bufferView " + std::to_string(user->second) + " refers to buffer " +
                         std::to_string(b) +
                         ", a meshopt fallback buffer, but has no meshopt compression: fallback "
                         "buffers hold no data Glint reads");
            buffer["uri"] = kPlaceholderUri;
            buffer["byteLength"] = 1;
            c->placeholders.insert(b);
            changed = true;
        }

    // Images cannot be read from compressed views (tinygltf reads them itself).
    if (const json* images = member(j, "images"); images && images->is_array())
        for (size_t i = 0; i < images->size(); ++i)
            if (const json* v = member((*images)[i], "bufferView");
                v && v->is_number_unsigned() && c->meshopt.count(v->get<size_t>()))
                ctx.fail("image " + std::to_string(i) + ": its bufferView " +
                         std::to_string(v->get<size_t>()) +
                         " is meshopt-compressed: Glint reads images from uncompressed "
                         "bufferViews only");

    if (!c->draco.empty() || !c->meshopt.empty()) ctx.compression = std::move(c);
    return changed;
}

void restoreCompression(Context& ctx) {
    if (!ctx.compression) return;
    Compression& c = *ctx.compression;
    auto& meshes = ctx.model.meshes;
    auto exists = [&](size_t m, size_t k) {
        return m < meshes.size() && k < meshes[m].primitives.size();
    };
    for (const auto& [at, indices] : c.removedIndices)
        if (exists(at.first, at.second)) meshes[at.first].primitives[at.second].indices = indices;

    // Which accessors each Draco primitive decodes. An accessor two primitives decode must come
    // from the same data.
    std::map<int, size_t> bufferViewOf;  // accessor: its Draco bufferView
    for (size_t i = 0; i < c.draco.size(); ++i) {
        const DracoPrimitive& d = c.draco[i];
        if (!exists(d.mesh, d.primitive))
            ctx.fail("mesh " + std::to_string(d.mesh) + ", primitive " +
                     std::to_string(d.primitive) + " has " + kDraco +
                     " but tinygltf did not read it");
        const tinygltf::Primitive& p = meshes[d.mesh].primitives[d.primitive];
        const std::string label = dracoLabel(ctx, d);
        auto add = [&](int accessor, DracoSource s, const std::string& role) {
            if (accessor < 0 || static_cast<size_t>(accessor) >= ctx.model.accessors.size())
                missing(ctx, "accessor", accessor, ctx.model.accessors.size(), label + " " + role);
            if (ctx.model.accessors[static_cast<size_t>(accessor)].sparse.isSparse)
                ctx.fail(label + ": accessor " + std::to_string(accessor) + " (" + role +
                         ") is sparse, which a Draco-compressed accessor must not be");
            auto [it, added] = c.dracoAccessors.emplace(accessor, s);
            auto [view, viewAdded] = bufferViewOf.emplace(accessor, d.bufferView);
            if (!added && (view->second != d.bufferView || it->second.indices != s.indices ||
                           it->second.uniqueId != s.uniqueId))
                ctx.fail(label + ": accessor " + std::to_string(accessor) + " (" + role +
                         ") is decoded from other Draco data by " +
                         dracoLabel(ctx, c.draco[it->second.primitive]));
        };
        if (p.indices >= 0) add(p.indices, {i, true, 0}, "indices");
        for (const auto& [name, id] : d.attributes) {
            auto it = p.attributes.find(name);
            if (it == p.attributes.end())
                ctx.fail(label + " names attribute " + name +
                         ", which the primitive does not have");
            add(it->second, {i, false, id}, name);
        }
    }
}

const std::vector<unsigned char>* dracoAccessor(const Context& ctx, int index) {
    if (!ctx.compression) return nullptr;
    Compression& c = *ctx.compression;
    auto source = c.dracoAccessors.find(index);
    if (source == c.dracoAccessors.end()) return nullptr;
    if (!c.draco[source->second.primitive].decoded) decodeDraco(ctx, c, source->second.primitive);
    auto it = c.accessors.find(index);
    return it == c.accessors.end() ? nullptr : &it->second;
}

std::optional<std::string_view> meshoptBufferView(const Context& ctx, int index) {
    if (!ctx.compression || index < 0) return std::nullopt;
    Compression& c = *ctx.compression;
    const size_t v = static_cast<size_t>(index);
    auto m = c.meshopt.find(v);
    if (m == c.meshopt.end()) return std::nullopt;
    auto it = c.views.find(v);
    if (it == c.views.end()) {
        std::vector<unsigned char> data = decodeMeshopt(ctx, c, v, m->second);
        c.bytes += data.size();
        it = c.views.emplace(v, std::move(data)).first;
    }
    return std::string_view(reinterpret_cast<const char*>(it->second.data()), it->second.size());
}

size_t decompressedBytes(const Context& ctx) {
    return ctx.compression ? ctx.compression->bytes : 0;
}

}  // namespace glint::gltf
