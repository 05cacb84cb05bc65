// KHR_draco_mesh_compression: a primitive's Draco data decoded with libdraco 1.5.5 (Debian 12)
// and written into the accessors the primitive names, in the layout each declares, after
// checking them against the decoded mesh (docs/scene-format.md, "Compressed meshes").

#include <draco/compression/decode.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <ctime>
#include <limits>
#include <type_traits>

#include "glint/io/gltf/gltf_compression.h"

namespace glint::gltf {
namespace {

/// libdraco's working memory while it decodes, per index of the primitive (an upper bound
/// measured on a 1M-triangle mesh, docs/performance.md "Compressed glTF"), on top of the output.
constexpr size_t kDracoBytesPerIndex = 64;
/// The CPU time libdraco may take for a file's Draco primitives together: GltfOptions::
/// dracoSeconds and so much per decoded index, 150 times what it takes here (0.13 us), so that
/// a slow machine or valgrind never reaches it. libdraco 1.5.5 can spend up to about 10 s (and
/// 256 MiB) on a few corrupt bytes whatever the mesh's size: texture coordinates' prediction
/// data hold a count of orientations it loops over without checking it against the mesh
/// (docs/robustness.md). One such primitive cannot be stopped; a file of many is, after the
/// first.
constexpr double kDracoSecondsPerIndex = 20e-6;

int componentSize(int componentType) {
    switch (componentType) {
        case TINYGLTF_COMPONENT_TYPE_BYTE:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
            return 1;
        case TINYGLTF_COMPONENT_TYPE_SHORT:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
            return 2;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
        case TINYGLTF_COMPONENT_TYPE_FLOAT:
            return 4;
        default:
            return 0;  // none glTF allows in an attribute
    }
}

/// A float in [0, 1] (or [-1, 1]) as the normalised integer T glTF defines.
template <typename T>
T quantize(float x) {
    constexpr double max = std::numeric_limits<T>::max();
    const double lo = std::is_signed_v<T> ? -1 : 0;
    return static_cast<T>(std::lround(std::clamp(double(x), lo, 1.0) * max));
}

/// Writes attribute `a` of every point as `components` values of T.
template <typename T>
void convertAttribute(const Context& ctx, const draco::PointAttribute& a, size_t points,
                      int components, bool normalized, unsigned char* out,
                      const std::string& label) {
    const bool fromFloat = a.data_type() == draco::DT_FLOAT32 || a.data_type() == draco::DT_FLOAT64;
    // A float attribute into a normalised integer accessor: libdraco would truncate, unscaled.
    const bool quantizing = std::is_integral_v<T> && normalized && fromFloat;
    T value[4];
    float f[4];
    const size_t size = static_cast<size_t>(components) * sizeof(T);
    for (size_t i = 0; i < points; ++i) {
        const draco::AttributeValueIndex v =
            a.mapped_index(draco::PointIndex(static_cast<uint32_t>(i)));
        bool ok;
        if (quantizing) {
            ok = a.ConvertValue<float>(v, static_cast<int8_t>(components), f);
            for (int k = 0; k < components && ok; ++k) {
                ok = !std::isnan(f[k]);
                value[k] = quantize<T>(f[k]);
            }
        } else {
            ok = a.ConvertValue<T>(v, static_cast<int8_t>(components), value);
        }
        if (!ok)
            ctx.fail(label + ": the value of point " + std::to_string(i) +
                     " does not fit the accessor's component type");
        std::memcpy(out + i * size, value, size);
    }
}

/// Decoded accessor `index` (a Draco attribute of `mesh`) in the accessor's layout.
std::vector<unsigned char> dracoAttribute(const Context& ctx, const draco::Mesh& mesh, int index,
                                          uint32_t uniqueId, const std::string& label) {
    const tinygltf::Accessor& acc = ctx.model.accessors[static_cast<size_t>(index)];
    const draco::PointAttribute* a = mesh.GetAttributeByUniqueId(uniqueId);
    if (!a)
        ctx.fail(label + ": the decoded mesh has no attribute of unique id " +
                 std::to_string(uniqueId));
    const size_t points = mesh.num_points();
    const int components = tinygltf::GetNumComponentsInType(static_cast<uint32_t>(acc.type));
    const int bytes = componentSize(acc.componentType);
    if (components < 1 || components > 4 || bytes == 0)
        ctx.fail(label + ": the accessor's type and component type are none a Draco attribute " +
                 "decodes to");
    if (acc.count != points)
        ctx.fail(label + ": the accessor's count is " + std::to_string(acc.count) +
                 ", but the decoded mesh has " + std::to_string(points) + " points");
    if (a->num_components() != components)
        ctx.fail(label + ": the decoded attribute has " + std::to_string(a->num_components()) +
                 " components, the accessor " + std::to_string(components));
    if (!a->is_mapping_identity() && a->indices_map_size() < points)
        ctx.fail(label + ": the decoded attribute maps fewer points than the mesh has");
    std::vector<unsigned char> out(points * static_cast<size_t>(components * bytes));
    auto convert = [&](auto zero) {
        convertAttribute<decltype(zero)>(ctx, *a, points, components, acc.normalized, out.data(),
                                         label);
    };
    switch (acc.componentType) {
        case TINYGLTF_COMPONENT_TYPE_BYTE:
            convert(int8_t{});
            break;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
            convert(uint8_t{});
            break;
        case TINYGLTF_COMPONENT_TYPE_SHORT:
            convert(int16_t{});
            break;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
            convert(uint16_t{});
            break;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
            convert(uint32_t{});
            break;
        default:
            convert(float{});
            break;
    }
    return out;
}

/// The decoded faces as indices accessor `index`, or (index -1) checked to be in vertex order.
std::vector<unsigned char> dracoIndices(const Context& ctx, const draco::Mesh& mesh, int index,
                                        const std::string& label) {
    const size_t faces = mesh.num_faces(), points = mesh.num_points();
    if (index < 0) {  // no indices: the triangles must be the points in order
        bool ordered = points == 3 * faces;
        for (uint32_t f = 0; f < faces && ordered; ++f) {
            const draco::Mesh::Face& face = mesh.face(draco::FaceIndex(f));
            for (uint32_t k = 0; k < 3; ++k) ordered = ordered && face[k].value() == 3 * f + k;
        }
        if (!ordered)
            ctx.fail(label +
                     ": the primitive has no indices, but the decoded triangles do not "
                     "take its points in order");
        return {};
    }
    const tinygltf::Accessor& acc = ctx.model.accessors[static_cast<size_t>(index)];
    const std::string what = label + " (indices, accessor " + std::to_string(index) + ")";
    if (acc.type != TINYGLTF_TYPE_SCALAR ||
        (acc.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
         acc.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
         acc.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT))
        ctx.fail(what + ": indices must be unsigned byte, short or int scalars");
    if (acc.count != 3 * faces)
        ctx.fail(what + ": the accessor's count is " + std::to_string(acc.count) +
                 ", but the decoded mesh has " + std::to_string(faces) + " triangles (" +
                 std::to_string(3 * faces) + " indices)");
    const size_t bytes = static_cast<size_t>(componentSize(acc.componentType));
    const uint64_t max = bytes == 4 ? UINT32_MAX : (uint64_t{1} << (8 * bytes)) - 1;
    if (points > 0 && points - 1 > max)
        ctx.fail(what + ": the decoded mesh's " + std::to_string(points) +
                 " points do not fit in the accessor's component type");
    std::vector<unsigned char> out(3 * faces * bytes);
    unsigned char* p = out.data();
    for (uint32_t f = 0; f < faces; ++f) {
        const draco::Mesh::Face& face = mesh.face(draco::FaceIndex(f));
        for (int k = 0; k < 3; ++k, p += bytes) {
            const uint32_t i = face[static_cast<size_t>(k)].value();
            if (i >= points)
                ctx.fail(what + ": decoded triangle " + std::to_string(f) + " refers to point " +
                         std::to_string(i) + " of " + std::to_string(points));
            if (bytes == 1) {
                *p = static_cast<uint8_t>(i);
            } else if (bytes == 2) {
                const uint16_t x = static_cast<uint16_t>(i);
                std::memcpy(p, &x, 2);
            } else {
                std::memcpy(p, &i, 4);
            }
        }
    }
    return out;
}

}  // namespace

void decodeDraco(const Context& ctx, Compression& c, size_t which) {
    DracoPrimitive& d = c.draco[which];
    d.decoded = true;
    const std::string label = dracoLabel(ctx, d);
    const tinygltf::Primitive& p = ctx.model.meshes[d.mesh].primitives[d.primitive];
    if (p.mode != TINYGLTF_MODE_TRIANGLES)
        ctx.fail(label + ": the primitive's mode is " + std::to_string(p.mode) +
                 ": Glint decodes Draco triangle lists (mode 4) only");

    // The output, and libdraco's working memory, before a byte is decoded.
    double output = 0, indices = 0;
    for (const auto& [accessor, source] : c.dracoAccessors)
        if (source.primitive == which) {
            const tinygltf::Accessor& a = ctx.model.accessors[static_cast<size_t>(accessor)];
            const double element =
                double(componentSize(a.componentType)) *
                double(
                    std::max(1, tinygltf::GetNumComponentsInType(static_cast<uint32_t>(a.type))));
            output += double(a.count) * element;
            if (source.indices) indices = double(a.count);
        }
    reserveDecoded(ctx, c, output + indices * kDracoBytesPerIndex, label);

    const std::string_view bytes =
        bufferViewBytes(ctx, static_cast<int>(d.bufferView), label + " data");
    draco::DecoderBuffer buffer;
    buffer.Init(bytes.data(), bytes.size());
    draco::Decoder decoder;
    const std::clock_t start = std::clock();
    auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
    c.dracoSeconds += double(std::clock() - start) / CLOCKS_PER_SEC;
    if (!decoded.ok() || !decoded.value())
        ctx.fail(label + ": libdraco cannot decode bufferView " + std::to_string(d.bufferView) +
                 " (" + std::to_string(bytes.size()) + " bytes): " +
                 (decoded.ok() ? std::string("no mesh") : decoded.status().error_msg_string()));
    const draco::Mesh& mesh = *decoded.value();
    c.dracoIndices += 3.0 * mesh.num_faces();
    if (c.dracoSeconds > ctx.options.dracoSeconds + kDracoSecondsPerIndex * c.dracoIndices)
        ctx.fail(label + ": libdraco took " + std::to_string(int(c.dracoSeconds)) +
                 " s of CPU time for " + std::to_string(size_t(c.dracoIndices / 3)) +
                 " triangles, far more than such data needs: the Draco data is corrupt");

    if (p.indices < 0) dracoIndices(ctx, mesh, -1, label);  // checks the triangles' order
    for (const auto& [accessor, source] : c.dracoAccessors) {
        if (source.primitive != which) continue;
        std::vector<unsigned char> data =
            source.indices
                ? dracoIndices(ctx, mesh, accessor, label)
                : dracoAttribute(ctx, mesh, accessor, source.uniqueId,
                                 label + " (attribute " + std::to_string(source.uniqueId) +
                                     ", accessor " + std::to_string(accessor) + ")");
        c.bytes += data.size();
        c.accessors[accessor] = std::move(data);
    }
}

}  // namespace glint::gltf
