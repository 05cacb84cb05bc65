// glTF meshes as MeshData: accessors checked against their buffer views and buffers before a
// byte is read, converted to float (normalised integers included), sparse accessors applied,
// and each mesh's primitives gathered into one MeshData, morphed by its morph targets, with
// tangents generated where a normal map needs them. Also the joints and weights of skinned
// vertices and the skins' matrices.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <initializer_list>
#include <limits>
#include <optional>

#include "glint/io/gltf/gltf_internal.h"
#include "glint/scene/tangents.h"

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

/// Checks that accessor `v`'s components are floats, or normalised integers of `normalised`
/// types (`what` says which, for the message).
void expectFloats(const Context& ctx, const AccessorView& v, std::initializer_list<int> normalised,
                  const char* what) {
    if (v.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT) return;
    if (v.normalized)
        for (int type : normalised)
            if (v.componentType == type) return;
    ctx.fail(v.label + ": its components must be " + what);
}

/// The checked accessors of one morph target of a primitive: displacements (VEC3, one per
/// vertex) of its POSITION, NORMAL and TANGENT; index -1 for those the target does not move.
struct TargetViews {
    AccessorView position, normal, tangent;
};

/// The checked accessors of a primitive.
struct PrimitiveViews {
    AccessorView position, normal, uv, uv1, color, tangent, indices;
    std::vector<TargetViews> targets;             ///< Its morph targets, in order.
    std::array<AccessorView, 2> joints, weights;  ///< JOINTS_n and WEIGHTS_n (skins only).
    bool hasNormal = false, hasUv = false, hasUv1 = false, hasColor = false, hasTangent = false;
    bool hasIndices = false;
    int jointSets = 0;  ///< JOINTS_0/WEIGHTS_0 (1), and _1 (2): read for skins only.
    /// Whether tangents are generated (its material has a normal map, it has no TANGENT and
    /// has the normal map's texture coordinates), and from which set (0 or 1).
    bool generateTangents = false;
    int tangentUvs = 0;
    size_t triangles = 0;

    bool hasExtras() const { return hasUv1 || hasColor || hasTangent || generateTangents; }
};

/// Checks primitive `k` of mesh `mesh`; false if it is skipped (with a warning when `report`).
/// With `skin`, also checks its joints and weights.
bool viewPrimitive(Context& ctx, int mesh, size_t k, bool report, PrimitiveViews& out,
                   bool skin = false) {
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
    // An attribute's accessor, checked by `check`, with one element per vertex.
    auto optional = [&](const std::string& name, AccessorView& view, auto check) {
        int index = attribute(p, name.c_str());
        if (index < 0) return false;
        view = viewAccessor(ctx, index, name + " of " + label);
        check(view);
        if (view.count != vertices)
            ctx.fail(view.label + ": it has " + std::to_string(view.count) +
                     " elements, but POSITION has " + std::to_string(vertices));
        return true;
    };
    auto elements = [&](int components, int type) {
        return [&ctx, components, type](const AccessorView& v) {
            expectComponents(ctx, v, components, type);
        };
    };
    constexpr int kUbyte = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
    constexpr int kUshort = TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
    out.hasNormal = optional("NORMAL", out.normal, elements(3, TINYGLTF_TYPE_VEC3));
    out.hasUv = optional("TEXCOORD_0", out.uv, elements(2, TINYGLTF_TYPE_VEC2));
    out.hasUv1 = optional("TEXCOORD_1", out.uv1, elements(2, TINYGLTF_TYPE_VEC2));
    out.hasColor = optional("COLOR_0", out.color, [&](const AccessorView& v) {
        const int type = ctx.model.accessors[static_cast<size_t>(v.index)].type;
        if (type != TINYGLTF_TYPE_VEC3 && type != TINYGLTF_TYPE_VEC4)
            ctx.fail(v.label + ": its elements are " + typeName(type) + ", not VEC3 or VEC4");
        expectFloats(ctx, v, {kUbyte, kUshort}, "floats, or normalised unsigned bytes or shorts");
    });
    out.hasTangent = optional("TANGENT", out.tangent, [&](const AccessorView& v) {
        expectComponents(ctx, v, 4, TINYGLTF_TYPE_VEC4);
        expectFloats(ctx, v, {TINYGLTF_COMPONENT_TYPE_BYTE, TINYGLTF_COMPONENT_TYPE_SHORT},
                     "floats, or normalised bytes or shorts");
    });
    // Morph targets (the glTF specification, 3.7.2.2): POSITION, NORMAL and TANGENT move;
    // other attributes are not morphed.
    out.targets.assign(p.targets.size(), {});
    for (size_t t = 0; t < p.targets.size(); ++t)
        for (const auto& [name, index] : p.targets[t]) {
            TargetViews& target = out.targets[t];
            AccessorView* view = name == "POSITION"  ? &target.position
                                 : name == "NORMAL"  ? &target.normal
                                 : name == "TANGENT" ? &target.tangent
                                                     : nullptr;
            if (!view) {
                if (report)
                    ctx.warnOnce("morph attributes", label + ": morph target attribute " + name +
                                                         " is ignored: only POSITION, NORMAL and "
                                                         "TANGENT are morphed");
                continue;
            }
            *view = viewAccessor(ctx, index,
                                 name + " of morph target " + std::to_string(t) + " of " + label);
            expectComponents(ctx, *view, 3, TINYGLTF_TYPE_VEC3);
            expectFloats(ctx, *view, {TINYGLTF_COMPONENT_TYPE_BYTE, TINYGLTF_COMPONENT_TYPE_SHORT},
                         "floats, or normalised bytes or shorts");
            if (view->count != vertices)
                ctx.fail(view->label + ": it has " + std::to_string(view->count) +
                         " elements, but POSITION has " + std::to_string(vertices));
        }
    for (int set = 0; skin && set < 2; ++set) {
        const std::string suffix = set == 0 ? "_0" : "_1";
        const size_t s = static_cast<size_t>(set);
        bool joints = optional("JOINTS" + suffix, out.joints[s], [&](const AccessorView& v) {
            expectComponents(ctx, v, 4, TINYGLTF_TYPE_VEC4);
            if (v.componentType != kUbyte && v.componentType != kUshort)
                ctx.fail(v.label + ": its components must be unsigned bytes or shorts");
        });
        bool weights = optional("WEIGHTS" + suffix, out.weights[s], [&](const AccessorView& v) {
            expectComponents(ctx, v, 4, TINYGLTF_TYPE_VEC4);
            expectFloats(ctx, v, {kUbyte, kUshort},
                         "floats, or normalised unsigned bytes or shorts");
        });
        if (joints != weights)
            ctx.fail(label + ": it has " + (joints ? "JOINTS" : "WEIGHTS") + suffix + " but no " +
                     (joints ? "WEIGHTS" : "JOINTS") + suffix);
        if (!joints) break;
        out.jointSets = set + 1;
    }
    size_t n = vertices;
    if (p.indices != -1) {
        out.indices = viewAccessor(ctx, p.indices, "indices of " + label);
        expectComponents(ctx, out.indices, 1, TINYGLTF_TYPE_SCALAR);
        out.hasIndices = true;
        n = out.indices.count;
    }
    if (p.material < -1 || p.material >= static_cast<int>(ctx.model.materials.size()))
        missing(ctx, "material", p.material, ctx.model.materials.size(), label);
    if (p.material >= 0 && !out.hasTangent) {
        const auto& normalMap = ctx.model.materials[static_cast<size_t>(p.material)].normalTexture;
        out.tangentUvs = normalMap.texCoord;
        out.generateTangents = normalMap.index >= 0 && ((normalMap.texCoord == 0 && out.hasUv) ||
                                                        (normalMap.texCoord == 1 && out.hasUv1));
    }
    out.triangles = trianglesOf(ctx, p.mode, n, label, report);
    return out.triangles > 0;
}

/// The displacements of one attribute of a primitive's vertices by its morph targets: each
/// target's accessor (checked by viewPrimitive) with its weight, none of weight 0.
using Displacements = std::vector<std::pair<const AccessorView*, double>>;

/// The displacements of the attribute `which` picks by the morph targets of `v` with `weights`
/// (one per target).
Displacements displacementsOf(const PrimitiveViews& v, AccessorView TargetViews::*which,
                              const std::vector<double>& weights) {
    Displacements out;
    for (size_t t = 0; t < v.targets.size(); ++t) {
        const AccessorView& view = v.targets[t].*which;
        if (weights[t] != 0 && view.index >= 0) out.push_back({&view, weights[t]});
    }
    return out;
}

/// Calls `add(i, w d)` for each vertex i and each displacement d, of weight w, of `moves`: the
/// glTF specification's morphing, base + sum of w_i d_i. Displacements must be finite.
template <typename F>
void displace(const Context& ctx, const Displacements& moves, F add) {
    std::vector<Vec3f> d;  // one target's displacements, sparse values applied
    for (const auto& [v, weight] : moves) {
        d.resize(v->count);
        forEachElement(ctx, *v, [&](size_t i, const float* c) { d[i] = {c[0], c[1], c[2]}; });
        for (size_t i = 0; i < v->count; ++i) {
            if (!isFinite(d[i]))
                ctx.fail(v->label + ": element " + std::to_string(i) +
                         " is not a finite displacement");
            add(i, weight * Vec3(d[i]));
        }
    }
}

/// Appends the positions of accessor `v` to `out`, moved by `moves`; returns the index of the
/// first.
uint32_t appendPositions(const Context& ctx, const AccessorView& v, MeshData& out,
                         const Displacements& moves) {
    const size_t first = out.positions.size();
    if (first + v.count >= MeshData::kNone)
        ctx.fail(v.label + ": the mesh has more than 4 billion vertices");
    out.positions.resize(first + v.count);
    Vec3f* p = out.positions.data() + first;
    forEachElement(ctx, v, [&](size_t i, const float* c) { p[i] = {c[0], c[1], c[2]}; });
    for (size_t i = 0; i < v.count; ++i)
        if (!std::isfinite(p[i].x) || !std::isfinite(p[i].y) || !std::isfinite(p[i].z))
            ctx.fail(v.label + ": element " + std::to_string(i) + " is not a finite position");
    if (moves.empty()) return static_cast<uint32_t>(first);
    displace(ctx, moves, [&](size_t i, const Vec3& d) { p[i] = Vec3f(Vec3(p[i]) + d); });
    for (size_t i = 0; i < v.count; ++i)
        if (!isFinite(p[i]))
            ctx.fail(v.label + ": element " + std::to_string(i) +
                     " is not a finite position once morphed");
    return static_cast<uint32_t>(first);
}

/// The same for normals, normalised after they are moved (zero stays zero).
uint32_t appendNormals(const Context& ctx, const AccessorView& v, MeshData& out,
                       const Displacements& moves) {
    const size_t first = out.normals.size();
    out.normals.resize(first + v.count);
    Vec3f* p = out.normals.data() + first;
    forEachElement(ctx, v, [&](size_t i, const float* c) { p[i] = {c[0], c[1], c[2]}; });
    for (size_t i = 0; i < v.count; ++i)
        if (!isFinite(p[i]))
            ctx.fail(v.label + ": element " + std::to_string(i) + " is not a finite normal");
    displace(ctx, moves, [&](size_t i, const Vec3& d) { p[i] = Vec3f(Vec3(p[i]) + d); });
    for (size_t i = 0; i < v.count; ++i) {
        Vec3 n(p[i]);
        if (!isFinite(n))
            ctx.fail(v.label + ": element " + std::to_string(i) +
                     " is not a finite normal once morphed");
        double len = length(n);
        p[i] = Vec3f(len > 0 ? n / len : Vec3(0));
    }
    return static_cast<uint32_t>(first);
}

/// The same for texture coordinates into `uvs` (MeshData::uvs or uv1s), turned to Glint's v
/// (up the image; glTF's runs down).
uint32_t appendUvs(const Context& ctx, const AccessorView& v, LargeVector<TexCoord>& uvs) {
    const size_t first = uvs.size();
    uvs.resize(first + v.count);
    TexCoord* p = uvs.data() + first;
    forEachElement(ctx, v, [&](size_t i, const float* c) { p[i] = {c[0], 1 - c[1]}; });
    for (size_t i = 0; i < v.count; ++i)
        if (!std::isfinite(p[i][0]) || !std::isfinite(p[i][1]))
            ctx.fail(v.label + ": element " + std::to_string(i) +
                     " is not a finite texture coordinate");
    return static_cast<uint32_t>(first);
}

/// The same for vertex colours: linear RGBA (glTF's are linear already), alpha 1 for VEC3,
/// clamped to [0, 1] as the base colour they multiply.
uint32_t appendColors(const Context& ctx, const AccessorView& v, MeshData& out) {
    const size_t first = out.colors.size();
    out.colors.resize(first + v.count);
    std::array<float, 4>* p = out.colors.data() + first;
    const bool rgba = v.components == 4;
    forEachElement(ctx, v, [&](size_t i, const float* c) {
        p[i] = {c[0], c[1], c[2], rgba ? c[3] : 1.0f};
    });
    for (size_t i = 0; i < v.count; ++i)
        for (float& x : p[i]) {
            if (!std::isfinite(x))
                ctx.fail(v.label + ": element " + std::to_string(i) + " is not a finite colour");
            x = std::clamp(x, 0.0f, 1.0f);
        }
    return static_cast<uint32_t>(first);
}

/// The same for tangents: xyz moved (w is not), then normalised (zero stays zero); w the sign
/// of the file's w.
uint32_t appendTangents(const Context& ctx, const AccessorView& v, MeshData& out,
                        const Displacements& moves) {
    const size_t first = out.tangents.size();
    out.tangents.resize(first + v.count);
    std::array<float, 4>* p = out.tangents.data() + first;
    forEachElement(ctx, v, [&](size_t i, const float* c) { p[i] = {c[0], c[1], c[2], c[3]}; });
    for (size_t i = 0; i < v.count; ++i)
        if (!isFinite(Vec3(p[i][0], p[i][1], p[i][2])) || !std::isfinite(p[i][3]))
            ctx.fail(v.label + ": element " + std::to_string(i) + " is not a finite tangent");
    displace(ctx, moves, [&](size_t i, const Vec3& d) {
        Vec3 t = Vec3(p[i][0], p[i][1], p[i][2]) + d;
        p[i] = {float(t.x), float(t.y), float(t.z), p[i][3]};
    });
    for (size_t i = 0; i < v.count; ++i) {
        Vec3 t(p[i][0], p[i][1], p[i][2]);
        if (!isFinite(t))
            ctx.fail(v.label + ": element " + std::to_string(i) +
                     " is not a finite tangent once morphed");
        double len = length(t);
        t = len > 0 ? t / len : Vec3(0);
        p[i] = {float(t.x), float(t.y), float(t.z), p[i][3] < 0 ? -1.0f : 1.0f};
    }
    return static_cast<uint32_t>(first);
}

/// Reads the joints and weights of a primitive's vertices into `out` from `first` on (where
/// its positions start); weights must be finite and not negative.
void readWeights(const Context& ctx, const PrimitiveViews& v, size_t first, VertexWeights& out) {
    if (out.vertices.size() < first + v.position.count)
        out.vertices.resize(first + v.position.count);
    VertexWeights::Vertex* w = out.vertices.data() + first;
    for (size_t set = 0; set < static_cast<size_t>(v.jointSets); ++set) {
        forEachElement(ctx, v.joints[set], [&](size_t i, const float* c) {
            for (size_t k = 0; k < 4; ++k) w[i].joints[4 * set + k] = static_cast<uint16_t>(c[k]);
        });
        forEachElement(ctx, v.weights[set], [&](size_t i, const float* c) {
            for (size_t k = 0; k < 4; ++k) {
                if (!std::isfinite(c[k]) || c[k] < 0)
                    ctx.fail(v.weights[set].label + ": element " + std::to_string(i) +
                             " has a weight that is negative or not finite");
                w[i].weights[4 * set + k] = c[k];
            }
        });
    }
}

}  // namespace

double MeshCounts::bytes() const {
    using Attribute = std::array<float, 4>;
    return double(positions) * sizeof(Vec3f) + double(normals) * sizeof(Vec3f) +
           double(uvs + uv1s) * sizeof(TexCoord) + double(colors) * sizeof(Attribute) +
           double(tangents + generatedTangents) * sizeof(Attribute) +
           double(triangles) * sizeof(MeshData::Triangle);
}

MeshCounts countMesh(Context& ctx, int mesh) {
    const tinygltf::Mesh& m = ctx.model.meshes[static_cast<size_t>(mesh)];
    MeshCounts c;
    // Accessors shared by primitives are read once.
    std::set<int> positions, normals, uvs, uv1s, colors, tangents;
    auto count = [](std::set<int>& seen, const AccessorView& view, size_t& n) {
        if (seen.insert(view.index).second) n += view.count;
    };
    morphTargetCount(ctx, mesh);
    for (size_t k = 0; k < m.primitives.size(); ++k) {
        PrimitiveViews v;
        if (!viewPrimitive(ctx, mesh, k, true, v)) continue;
        count(positions, v.position, c.positions);
        if (v.hasNormal) count(normals, v.normal, c.normals);
        if (v.hasUv) count(uvs, v.uv, c.uvs);
        if (v.hasUv1) count(uv1s, v.uv1, c.uv1s);
        if (v.hasColor) count(colors, v.color, c.colors);
        if (v.hasTangent) count(tangents, v.tangent, c.tangents);
        // Generated tangents: one per corner at most (a vertex per corner, each of its own).
        if (v.generateTangents) {
            c.generatedTangents += 3 * v.triangles;
            c.largestGeneration = std::max(c.largestGeneration, v.triangles);
        }
        c.triangles += v.triangles;
        if (v.hasNormal) c.normalTriangles += v.triangles;
        if (v.hasUv) c.uvTriangles += v.triangles;
        if (v.hasExtras()) c.extraTriangles += v.triangles;
    }
    return c;
}

size_t morphTargetCount(const Context& ctx, int mesh) {
    const tinygltf::Mesh& m = ctx.model.meshes[static_cast<size_t>(mesh)];
    const std::string label = describe("mesh", static_cast<size_t>(mesh), m.name);
    auto targets = [](size_t n) {
        return std::to_string(n) + (n == 1 ? " morph target" : " morph targets");
    };
    const size_t n = m.primitives.empty() ? 0 : m.primitives[0].targets.size();
    for (size_t k = 1; k < m.primitives.size(); ++k)
        if (m.primitives[k].targets.size() != n)
            ctx.fail(primitiveLabel(ctx, mesh, k) + ": it has " +
                     targets(m.primitives[k].targets.size()) + ", but primitive 0 has " +
                     std::to_string(n) + " (every primitive of a mesh must have as many)");
    if (!m.weights.empty()) {
        if (m.weights.size() != n)
            ctx.fail(label + ": it has " + std::to_string(m.weights.size()) + " weights, but " +
                     targets(n) + " (one weight per target)");
        for (size_t i = 0; i < n; ++i)
            if (!std::isfinite(m.weights[i]))
                ctx.fail(label + ": weight " + std::to_string(i) + " is not a finite number");
    }
    return n;
}

MeshData readMesh(Context& ctx, int mesh, const MeshCounts& counts, Materials& materials,
                  VertexWeights* weights, const std::vector<double>* morphWeights) {
    const tinygltf::Mesh& m = ctx.model.meshes[static_cast<size_t>(mesh)];
    // The weights of its morph targets: given, the mesh's own, or zeros (the base shape).
    const size_t targets = morphTargetCount(ctx, mesh);
    std::vector<double> morph(targets, 0.0);
    if (morphWeights) {
        const std::string label = describe("mesh", static_cast<size_t>(mesh), m.name);
        if (morphWeights->size() != targets)
            ctx.fail(label + ": " + std::to_string(morphWeights->size()) +
                     " morph target weights are given for its " + std::to_string(targets) +
                     (targets == 1 ? " morph target" : " morph targets"));
        for (size_t i = 0; i < targets; ++i)
            if (!std::isfinite((*morphWeights)[i]))
                ctx.fail(label + ": morph target weight " + std::to_string(i) +
                         " is not a finite number");
        morph = *morphWeights;
    } else if (!m.weights.empty()) {
        morph = m.weights;  // checked by morphTargetCount
    }
    MeshData out;
    out.name = ctx.file;
    out.positions.reserve(counts.positions);
    out.normals.reserve(counts.normals);
    out.uvs.reserve(counts.uvs);
    out.uv1s.reserve(counts.uv1s);
    out.colors.reserve(counts.colors);
    out.tangents.reserve(counts.tangents);
    out.triangles.reserve(counts.triangles);
    // Where each accessor's elements start in `out`, and each glTF material's index there.
    std::map<int, uint32_t> positionBase, normalBase, uvBase, uv1Base, colorBase, tangentBase;
    std::map<int, uint32_t> materialIds;
    auto base = [&](std::map<int, uint32_t>& bases, const AccessorView& v, auto append) {
        auto [it, added] = bases.emplace(v.index, 0);
        if (added) it->second = append(ctx, v, out);
        return it->second;
    };
    auto appendUv0 = [](const Context& c, const AccessorView& v, MeshData& o) {
        return appendUvs(c, v, o.uvs);
    };
    auto appendUv1 = [](const Context& c, const AccessorView& v, MeshData& o) {
        return appendUvs(c, v, o.uv1s);
    };
    for (size_t k = 0; k < m.primitives.size(); ++k) {
        const tinygltf::Primitive& p = m.primitives[k];
        PrimitiveViews v;
        if (!viewPrimitive(ctx, mesh, k, false, v, weights != nullptr))
            continue;  // countMesh has warned
        // Positions, normals and tangents are morphed where they are appended: by the targets
        // of the first primitive that uses their accessors.
        auto morphed = [&](auto append, AccessorView TargetViews::*which) {
            return
                [&v, &morph, append, which](const Context& c, const AccessorView& a, MeshData& o) {
                    return append(c, a, o, displacementsOf(v, which, morph));
                };
        };
        const bool newPositions = !positionBase.contains(v.position.index);
        const uint32_t pBase =
            base(positionBase, v.position, morphed(appendPositions, &TargetViews::position));
        if (weights && newPositions) readWeights(ctx, v, pBase, *weights);
        const uint32_t nBase =
            v.hasNormal ? base(normalBase, v.normal, morphed(appendNormals, &TargetViews::normal))
                        : 0;
        const uint32_t uBase = v.hasUv ? base(uvBase, v.uv, appendUv0) : 0;
        const uint32_t u1Base = v.hasUv1 ? base(uv1Base, v.uv1, appendUv1) : 0;
        const uint32_t cBase = v.hasColor ? base(colorBase, v.color, appendColors) : 0;
        const uint32_t tBase = v.hasTangent ? base(tangentBase, v.tangent,
                                                   morphed(appendTangents, &TargetViews::tangent))
                                            : 0;
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
            if (v.hasUv1) c.uv1 = u1Base + i;
            if (v.hasColor) c.color = cBase + i;
            if (v.hasTangent) c.tangent = tBase + i;
            return c;
        };
        auto add = [&](size_t a, size_t b, size_t c) {
            out.triangles.push_back({{corner(a), corner(b), corner(c)}, material});
        };
        const size_t firstTriangle = out.triangles.size();
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
        // The glTF specification: without TANGENT, a normal-mapped primitive's tangents are
        // MikkTSpace's, from its positions, normals and the normal map's coordinates.
        if (v.generateTangents) {
            TangentRequest request;
            request.first = firstTriangle;
            request.last = out.triangles.size();
            request.secondUvs = v.tangentUvs == 1;
            generateTangents(out, request);
        }
    }
    return out;
}

std::vector<Mat4> readMatrices(const Context& ctx, int index, size_t count,
                               const std::string& user) {
    AccessorView v = viewAccessor(ctx, index, user);
    expectComponents(ctx, v, 16, TINYGLTF_TYPE_MAT4);
    if (v.count < count)
        ctx.fail(v.label + ": it has " + std::to_string(v.count) +
                 (v.count == 1 ? " matrix" : " matrices") + ", fewer than the " +
                 std::to_string(count) + " its joints need");
    std::vector<Mat4> out(count);  // the first `count`: any more are not used
    forEachElement(ctx, v, [&](size_t i, const float* c) {
        if (i >= count) return;
        for (int col = 0; col < 4; ++col)  // column by column, as glTF stores them
            for (int row = 0; row < 4; ++row) out[i].m[row][col] = c[col * 4 + row];
    });
    for (size_t i = 0; i < count; ++i) {
        Mat4& m = out[i];
        for (const auto& row : m.m)
            for (double x : row)
                if (!std::isfinite(x))
                    ctx.fail(v.label + ": matrix " + std::to_string(i) + " is not finite");
        // Stored as floats: the last row is 0 0 0 1 to within their precision.
        if (std::abs(m.m[3][0]) > 1e-5 || std::abs(m.m[3][1]) > 1e-5 ||
            std::abs(m.m[3][2]) > 1e-5 || std::abs(m.m[3][3] - 1) > 1e-5)
            ctx.fail(v.label + ": matrix " + std::to_string(i) +
                     " is not affine (its last row must be 0 0 0 1)");
        m.m[3][0] = m.m[3][1] = m.m[3][2] = 0;
        m.m[3][3] = 1;
    }
    return out;
}

FloatElements readFloats(const Context& ctx, int index, const std::string& user, bool normalised) {
    AccessorView v = viewAccessor(ctx, index, user);
    if (normalised)
        expectFloats(ctx, v,
                     {TINYGLTF_COMPONENT_TYPE_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
                      TINYGLTF_COMPONENT_TYPE_SHORT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT},
                     "floats, or normalised bytes or shorts");
    else
        expectFloats(ctx, v, {}, "floats");
    FloatElements out;
    out.count = v.count;
    out.components = static_cast<size_t>(v.components);
    out.label = v.label;
    out.values.resize(out.count * out.components);
    forEachElement(ctx, v, [&](size_t i, const float* c) {
        std::copy_n(c, out.components, out.values.data() + i * out.components);
    });
    for (size_t i = 0; i < out.values.size(); ++i)
        if (!std::isfinite(out.values[i]))
            ctx.fail(v.label + ": element " + std::to_string(i / out.components) +
                     " is not finite");
    return out;
}

}  // namespace glint::gltf
