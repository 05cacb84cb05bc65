// glTF meshes as MeshData: accessors checked against their buffer views and buffers before a
// byte is read, converted to float (normalised integers included), sparse accessors applied,
// and each mesh's primitives gathered into one MeshData.

#include <cmath>
#include <cstring>
#include <limits>
#include <optional>

#include "glint/io/gltf/gltf_internal.h"

namespace glint::gltf {
namespace {

/// Bytes of one component of `componentType`, 0 for types glTF does not define.
int componentBytes(int componentType) {
    switch (componentType) {
        case TINYGLTF_COMPONENT_TYPE_BYTE:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
            return 1;
        case TINYGLTF_COMPONENT_TYPE_SHORT:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
            return 2;
        case TINYGLTF_COMPONENT_TYPE_INT:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
        case TINYGLTF_COMPONENT_TYPE_FLOAT:
            return 4;
        case TINYGLTF_COMPONENT_TYPE_DOUBLE:
            return 8;
        default:
            return 0;
    }
}

const char* typeName(int type) {
    switch (type) {
        case TINYGLTF_TYPE_SCALAR:
            return "SCALAR";
        case TINYGLTF_TYPE_VEC2:
            return "VEC2";
        case TINYGLTF_TYPE_VEC3:
            return "VEC3";
        case TINYGLTF_TYPE_VEC4:
            return "VEC4";
        case TINYGLTF_TYPE_MAT2:
            return "MAT2";
        case TINYGLTF_TYPE_MAT3:
            return "MAT3";
        case TINYGLTF_TYPE_MAT4:
            return "MAT4";
        default:
            return "an unknown type";
    }
}

/// Whether `count` items of `size` bytes, `stride` bytes apart from `offset`, fit in `limit`
/// bytes (count > 0), without overflow.
bool fits(size_t offset, size_t stride, size_t count, size_t size, size_t limit) {
    if (offset > limit || size > limit - offset) return false;
    return count - 1 <= (stride == 0 ? count - 1 : (limit - offset - size) / stride);
}

/// Where an accessor's elements lie, checked (docs/scene-format.md, "glTF", for the rules).
struct AccessorView {
    int index = -1;
    const unsigned char* data = nullptr;  ///< First element; null: zeros (no bufferView).
    size_t count = 0, stride = 0;
    int componentType = 0, components = 0, bytes = 0;  ///< bytes: of one component
    bool normalized = false;
    std::string label;  ///< "accessor 3 (POSITION of mesh 0, primitive 1)"
};

AccessorView viewAccessor(const Context& ctx, int index, const std::string& user) {
    const auto& accessors = ctx.model.accessors;
    if (index < 0 || static_cast<size_t>(index) >= accessors.size())
        missing(ctx, "accessor", index, accessors.size(), user);
    const tinygltf::Accessor& a = accessors[static_cast<size_t>(index)];
    AccessorView v;
    v.index = index;
    v.label = "accessor " + std::to_string(index) + " (" + user + ")";
    v.componentType = a.componentType;
    v.bytes = componentBytes(a.componentType);
    if (v.bytes == 0)
        ctx.fail(v.label + ": component type " + std::to_string(a.componentType) +
                 " is not one glTF defines");
    v.components = tinygltf::GetNumComponentsInType(static_cast<uint32_t>(a.type));
    if (v.components <= 0) ctx.fail(v.label + ": unknown element type");
    v.count = a.count;
    v.normalized = a.normalized;
    const size_t element = static_cast<size_t>(v.bytes) * static_cast<size_t>(v.components);
    v.stride = element;
    if (const std::vector<unsigned char>* decoded = dracoAccessor(ctx, index)) {
        v.data = decoded->data();  // decoded from Draco, tightly, as the accessor declares
        return v;
    }
    if (a.bufferView < -1)
        missing(ctx, "bufferView", a.bufferView, ctx.model.bufferViews.size(), v.label);
    if (a.bufferView == -1) return v;  // zeros, perhaps with sparse values
    std::string_view bytes = bufferViewBytes(ctx, a.bufferView, v.label);
    const tinygltf::BufferView& bv = ctx.model.bufferViews[static_cast<size_t>(a.bufferView)];
    if (bv.byteStride != 0) {
        if (bv.byteStride < element)
            ctx.fail(v.label + ": its elements of " + std::to_string(element) +
                     " bytes are longer than the stride of bufferView " +
                     std::to_string(a.bufferView) + " (" + std::to_string(bv.byteStride) +
                     " bytes)");
        v.stride = bv.byteStride;
    }
    if (v.count > 0 && !fits(a.byteOffset, v.stride, v.count, element, bytes.size()))
        ctx.fail(v.label + ": its " + std::to_string(v.count) + " elements of " +
                 std::to_string(element) + " bytes, " + std::to_string(v.stride) +
                 " bytes apart from offset " + std::to_string(a.byteOffset) +
                 ", do not fit in bufferView " + std::to_string(a.bufferView) + " (" +
                 std::to_string(bytes.size()) + " bytes)");
    v.data = reinterpret_cast<const unsigned char*>(bytes.data()) + (v.count ? a.byteOffset : 0);
    return v;
}

/// Component `c` of element `i` as a float, normalised integers mapped to [0, 1] or [-1, 1].
float component(const unsigned char* element, int c, int type, bool normalized) {
    auto get = [&](auto zero) {
        decltype(zero) x;
        std::memcpy(&x, element + static_cast<size_t>(c) * sizeof x, sizeof x);
        return x;
    };
    switch (type) {
        case TINYGLTF_COMPONENT_TYPE_BYTE: {
            float x = get(int8_t{});
            return normalized ? std::max(x / 127.0f, -1.0f) : x;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: {
            float x = get(uint8_t{});
            return normalized ? x / 255.0f : x;
        }
        case TINYGLTF_COMPONENT_TYPE_SHORT: {
            float x = get(int16_t{});
            return normalized ? std::max(x / 32767.0f, -1.0f) : x;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
            float x = get(uint16_t{});
            return normalized ? x / 65535.0f : x;
        }
        case TINYGLTF_COMPONENT_TYPE_INT:
            return static_cast<float>(get(int32_t{}));
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
            return static_cast<float>(get(uint32_t{}));
        case TINYGLTF_COMPONENT_TYPE_FLOAT:
            return get(float{});
        default: {  // double; beyond the float range it becomes infinite, and is rejected
            double x = get(double{});
            if (std::abs(x) <= std::numeric_limits<float>::max()) return static_cast<float>(x);
            return x > 0 ? std::numeric_limits<float>::infinity()
                         : (x < 0 ? -std::numeric_limits<float>::infinity()
                                  : std::numeric_limits<float>::quiet_NaN());
        }
    }
}

/// Checks that accessor `v` has elements of `components` components.
void expectComponents(const Context& ctx, const AccessorView& v, int components, int type) {
    const tinygltf::Accessor& a = ctx.model.accessors[static_cast<size_t>(v.index)];
    if (v.components != components || a.type != type)
        ctx.fail(v.label + ": its elements are " + typeName(a.type) + ", not " + typeName(type));
}

/// An unsigned integer of `bytes` (1, 2 or 4) bytes at `p`.
uint32_t unsignedAt(const unsigned char* p, int bytes) {
    if (bytes == 1) return *p;
    if (bytes == 2) {
        uint16_t x;
        std::memcpy(&x, p, 2);
        return x;
    }
    uint32_t x;
    std::memcpy(&x, p, 4);
    return x;
}

/// Calls `f(i, element)` for each substitution of sparse accessor `v`: element `i` takes the
/// value at `element` (laid out as the accessor's elements).
template <typename F>
void forEachSparse(const Context& ctx, const AccessorView& v, F f) {
    const tinygltf::Accessor& a = ctx.model.accessors[static_cast<size_t>(v.index)];
    const auto& s = a.sparse;
    if (s.count < 1 || static_cast<size_t>(s.count) > v.count)
        ctx.fail(v.label + ": its sparse count " + std::to_string(s.count) +
                 " is not between 1 and its count " + std::to_string(v.count));
    const size_t n = static_cast<size_t>(s.count);
    int indexBytes = s.indices.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE    ? 1
                     : s.indices.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ? 2
                     : s.indices.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT   ? 4
                                                                                         : 0;
    if (indexBytes == 0)
        ctx.fail(v.label + ": its sparse indices must be unsigned bytes, shorts or ints");
    const size_t element = static_cast<size_t>(v.bytes) * static_cast<size_t>(v.components);
    auto range = [&](int view, int offset, size_t size, const char* what) {
        std::string_view bytes = bufferViewBytes(ctx, view, v.label + " sparse " + what);
        if (offset < 0 || !fits(static_cast<size_t>(offset), size, n, size, bytes.size()))
            ctx.fail(v.label + ": its " + std::to_string(n) + " sparse " + what + " from offset " +
                     std::to_string(offset) + " do not fit in bufferView " + std::to_string(view) +
                     " (" + std::to_string(bytes.size()) + " bytes)");
        return reinterpret_cast<const unsigned char*>(bytes.data()) + offset;
    };
    const unsigned char* indices = range(s.indices.bufferView, s.indices.byteOffset,
                                         static_cast<size_t>(indexBytes), "indices");
    const unsigned char* values =
        range(s.values.bufferView, s.values.byteOffset, element, "values");
    for (size_t k = 0; k < n; ++k) {
        uint32_t i = unsignedAt(indices + k * static_cast<size_t>(indexBytes), indexBytes);
        if (i >= v.count)
            ctx.fail(v.label + ": sparse index " + std::to_string(k) + " is " + std::to_string(i) +
                     ", beyond its " + std::to_string(v.count) + " elements");
        f(i, values + k * element);
    }
}

bool isSparse(const Context& ctx, const AccessorView& v) {
    return ctx.model.accessors[static_cast<size_t>(v.index)].sparse.isSparse;
}

/// Calls `f(i, c)` for each element i of accessor `v`, with `c` its components as floats
/// (zeros without a bufferView), then again for each element a sparse accessor replaces, with
/// the new value: `f` stores by index. No copy of the accessor is made.
template <typename F>
void forEachElement(const Context& ctx, const AccessorView& v, F f) {
    const size_t n = static_cast<size_t>(v.components);
    float c[16] = {};  // components: at most 16 (MAT4)
    auto convert = [&](size_t i, const unsigned char* element) {
        for (size_t k = 0; k < n; ++k)
            c[k] = component(element, static_cast<int>(k), v.componentType, v.normalized);
        f(i, static_cast<const float*>(c));
    };
    if (v.data && v.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT) {
        for (size_t i = 0; i < v.count; ++i) {
            std::memcpy(c, v.data + i * v.stride, n * sizeof(float));
            f(i, static_cast<const float*>(c));
        }
    } else if (v.data) {
        for (size_t i = 0; i < v.count; ++i) convert(i, v.data + i * v.stride);
    } else {
        for (size_t i = 0; i < v.count; ++i) f(i, static_cast<const float*>(c));
    }
    if (isSparse(ctx, v)) forEachSparse(ctx, v, convert);
}

/// Vertex index `k` of indices accessor `v`.
class IndexReader {
  public:
    IndexReader(const Context& ctx, const AccessorView& v) : v_(v) {
        if (v.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
            v.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
            v.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
            ctx.fail(v.label + ": indices must be unsigned bytes, shorts or ints");
        if (!isSparse(ctx, v)) return;
        // Sparse indices (rare) are gathered first.
        sparse_.assign(v.count, 0);
        if (v.data)
            for (size_t i = 0; i < v.count; ++i)
                sparse_[i] = unsignedAt(v.data + i * v.stride, v.bytes);
        forEachSparse(ctx, v, [&](size_t i, const unsigned char* element) {
            sparse_[i] = unsignedAt(element, v.bytes);
        });
    }
    uint32_t operator[](size_t k) const {
        if (!sparse_.empty()) return sparse_[k];
        return v_.data ? unsignedAt(v_.data + k * v_.stride, v_.bytes) : 0;
    }

  private:
    const AccessorView& v_;
    std::vector<uint32_t> sparse_;
};

/// "mesh 0 'Cube', primitive 1"
std::string primitiveLabel(const Context& ctx, int mesh, size_t primitive) {
    return describe("mesh", static_cast<size_t>(mesh),
                    ctx.model.meshes[static_cast<size_t>(mesh)].name) +
           ", primitive " + std::to_string(primitive);
}

/// Triangles a primitive of `mode` with `n` vertices (or indices) makes: 0 for points and
/// lines, which Glint skips. Warns about what it skips when `report`.
size_t trianglesOf(Context& ctx, int mode, size_t n, const std::string& label, bool report) {
    switch (mode) {
        case TINYGLTF_MODE_TRIANGLES:
            if (n % 3 != 0 && report)
                ctx.warn(label + ": " + std::to_string(n) +
                         " vertices do not make whole triangles: the last " +
                         std::to_string(n % 3) + " are ignored");
            return n / 3;
        case TINYGLTF_MODE_TRIANGLE_STRIP:
        case TINYGLTF_MODE_TRIANGLE_FAN:
            return n >= 3 ? n - 2 : 0;
        case TINYGLTF_MODE_POINTS:
        case TINYGLTF_MODE_LINE:
        case TINYGLTF_MODE_LINE_LOOP:
        case TINYGLTF_MODE_LINE_STRIP:
            if (report)
                ctx.warnOnce("lines", label +
                                          ": points and lines have no area and are not rendered: "
                                          "primitives of these modes are skipped");
            return 0;
        default:
            ctx.fail(label + ": mode " + std::to_string(mode) + " is not one glTF defines");
    }
}

/// The accessor of attribute `name` of primitive `p`, or -1.
int attribute(const tinygltf::Primitive& p, const char* name) {
    auto it = p.attributes.find(name);
    return it == p.attributes.end() ? -1 : it->second;
}

/// The checked accessors of a primitive.
struct PrimitiveViews {
    AccessorView position, normal, uv, indices;
    bool hasNormal = false, hasUv = false, hasIndices = false;
    size_t triangles = 0;
};

/// Checks primitive `k` of mesh `mesh`; false if it is skipped (with a warning when `report`).
bool viewPrimitive(Context& ctx, int mesh, size_t k, bool report, PrimitiveViews& out) {
    const tinygltf::Primitive& p = ctx.model.meshes[static_cast<size_t>(mesh)].primitives[k];
    const std::string label = primitiveLabel(ctx, mesh, k);
    int pos = attribute(p, "POSITION");
    if (pos < 0) {
        if (report) ctx.warn(label + " has no POSITION attribute: it is skipped");
        return false;
    }
    out.position = viewAccessor(ctx, pos, "POSITION of " + label);
    expectComponents(ctx, out.position, 3, TINYGLTF_TYPE_VEC3);
    const size_t vertices = out.position.count;
    auto optional = [&](const char* name, int components, int type, AccessorView& view) {
        int index = attribute(p, name);
        if (index < 0) return false;
        view = viewAccessor(ctx, index, std::string(name) + " of " + label);
        expectComponents(ctx, view, components, type);
        if (view.count != vertices)
            ctx.fail(view.label + ": it has " + std::to_string(view.count) +
                     " elements, but POSITION has " + std::to_string(vertices));
        return true;
    };
    out.hasNormal = optional("NORMAL", 3, TINYGLTF_TYPE_VEC3, out.normal);
    out.hasUv = optional("TEXCOORD_0", 2, TINYGLTF_TYPE_VEC2, out.uv);
    size_t n = vertices;
    if (p.indices != -1) {
        out.indices = viewAccessor(ctx, p.indices, "indices of " + label);
        expectComponents(ctx, out.indices, 1, TINYGLTF_TYPE_SCALAR);
        out.hasIndices = true;
        n = out.indices.count;
    }
    if (p.material < -1 || p.material >= static_cast<int>(ctx.model.materials.size()))
        missing(ctx, "material", p.material, ctx.model.materials.size(), label);
    out.triangles = trianglesOf(ctx, p.mode, n, label, report);
    return out.triangles > 0;
}

/// Appends the positions of accessor `v` to `out`; returns the index of the first.
uint32_t appendPositions(const Context& ctx, const AccessorView& v, MeshData& out) {
    const size_t first = out.positions.size();
    if (first + v.count >= MeshData::kNone)
        ctx.fail(v.label + ": the mesh has more than 4 billion vertices");
    out.positions.resize(first + v.count);
    Vec3f* p = out.positions.data() + first;
    forEachElement(ctx, v, [&](size_t i, const float* c) { p[i] = {c[0], c[1], c[2]}; });
    for (size_t i = 0; i < v.count; ++i)
        if (!std::isfinite(p[i].x) || !std::isfinite(p[i].y) || !std::isfinite(p[i].z))
            ctx.fail(v.label + ": element " + std::to_string(i) + " is not a finite position");
    return static_cast<uint32_t>(first);
}

/// The same for normals, normalised (zero stays zero).
uint32_t appendNormals(const Context& ctx, const AccessorView& v, MeshData& out) {
    const size_t first = out.normals.size();
    out.normals.resize(first + v.count);
    Vec3f* p = out.normals.data() + first;
    forEachElement(ctx, v, [&](size_t i, const float* c) { p[i] = {c[0], c[1], c[2]}; });
    for (size_t i = 0; i < v.count; ++i) {
        Vec3 n(p[i]);
        if (!isFinite(n))
            ctx.fail(v.label + ": element " + std::to_string(i) + " is not a finite normal");
        double len = length(n);
        p[i] = Vec3f(len > 0 ? n / len : Vec3(0));
    }
    return static_cast<uint32_t>(first);
}

/// The same for texture coordinates, turned to Glint's v (up the image; glTF's runs down).
uint32_t appendUvs(const Context& ctx, const AccessorView& v, MeshData& out) {
    const size_t first = out.uvs.size();
    out.uvs.resize(first + v.count);
    TexCoord* p = out.uvs.data() + first;
    forEachElement(ctx, v, [&](size_t i, const float* c) { p[i] = {c[0], 1 - c[1]}; });
    for (size_t i = 0; i < v.count; ++i)
        if (!std::isfinite(p[i][0]) || !std::isfinite(p[i][1]))
            ctx.fail(v.label + ": element " + std::to_string(i) +
                     " is not a finite texture coordinate");
    return static_cast<uint32_t>(first);
}

}  // namespace

MeshCounts countMesh(Context& ctx, int mesh) {
    const tinygltf::Mesh& m = ctx.model.meshes[static_cast<size_t>(mesh)];
    MeshCounts c;
    std::set<int> positions, normals, uvs;  // accessors shared by primitives are read once
    for (size_t k = 0; k < m.primitives.size(); ++k) {
        PrimitiveViews v;
        if (!m.primitives[k].targets.empty())
            ctx.warnOnce("morph", "morph targets are not supported: meshes keep their base shape");
        if (!viewPrimitive(ctx, mesh, k, true, v)) continue;
        if (positions.insert(v.position.index).second) c.positions += v.position.count;
        if (v.hasNormal && normals.insert(v.normal.index).second) c.normals += v.normal.count;
        if (v.hasUv && uvs.insert(v.uv.index).second) c.uvs += v.uv.count;
        c.triangles += v.triangles;
        if (v.hasNormal) c.normalTriangles += v.triangles;
        if (v.hasUv) c.uvTriangles += v.triangles;
    }
    return c;
}

MeshData readMesh(Context& ctx, int mesh, const MeshCounts& counts, Materials& materials) {
    const tinygltf::Mesh& m = ctx.model.meshes[static_cast<size_t>(mesh)];
    MeshData out;
    out.name = ctx.file;
    out.positions.reserve(counts.positions);
    out.normals.reserve(counts.normals);
    out.uvs.reserve(counts.uvs);
    out.triangles.reserve(counts.triangles);
    // Where each accessor's elements start in `out`, and each glTF material's index there.
    std::map<int, uint32_t> positionBase, normalBase, uvBase, materialIds;
    auto base = [&](std::map<int, uint32_t>& bases, const AccessorView& v, auto append) {
        auto [it, added] = bases.emplace(v.index, 0);
        if (added) it->second = append(ctx, v, out);
        return it->second;
    };
    for (size_t k = 0; k < m.primitives.size(); ++k) {
        const tinygltf::Primitive& p = m.primitives[k];
        PrimitiveViews v;
        if (!viewPrimitive(ctx, mesh, k, false, v)) continue;  // countMesh has warned
        const uint32_t pBase = base(positionBase, v.position, appendPositions);
        const uint32_t nBase = v.hasNormal ? base(normalBase, v.normal, appendNormals) : 0;
        const uint32_t uBase = v.hasUv ? base(uvBase, v.uv, appendUvs) : 0;
        uint32_t material = MeshData::kNone;
        if (p.material >= 0) {
            auto [it, added] = materialIds.emplace(p.material, 0);
            if (added) {
                it->second = static_cast<uint32_t>(out.materials.size());
                out.materials.push_back(materials.get(p.material));
            }
            material = it->second;
        }

        std::optional<IndexReader> indices;
        if (v.hasIndices) indices.emplace(ctx, v.indices);
        const size_t vertices = v.position.count;
        auto corner = [&](size_t at) {
            uint32_t i = indices ? (*indices)[at] : static_cast<uint32_t>(at);
            if (i >= vertices)
                ctx.fail(v.indices.label + ": index " + std::to_string(at) + " is " +
                         std::to_string(i) + ", but the primitive has " + std::to_string(vertices) +
                         " vertices");
            MeshData::Corner c;
            c.position = pBase + i;
            if (v.hasNormal) c.normal = nBase + i;
            if (v.hasUv) c.uv = uBase + i;
            return c;
        };
        auto add = [&](size_t a, size_t b, size_t c) {
            out.triangles.push_back({{corner(a), corner(b), corner(c)}, material});
        };
        for (size_t t = 0; t < v.triangles; ++t) {
            if (p.mode == TINYGLTF_MODE_TRIANGLE_STRIP)
                add(t, t + 1 + t % 2, t + 2 - t % 2);  // every other one turned, as glTF orders
            else if (p.mode == TINYGLTF_MODE_TRIANGLE_FAN)
                add(t + 1, t + 2, 0);
            else
                add(3 * t, 3 * t + 1, 3 * t + 2);
        }
        if (v.hasNormal) out.normalTriangles += v.triangles;
        if (v.hasUv) out.uvTriangles += v.triangles;
    }
    return out;
}

}  // namespace glint::gltf
