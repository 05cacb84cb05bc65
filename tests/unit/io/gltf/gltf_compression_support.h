#pragma once
// Compressed glTF assets written by the tests themselves (gltf_compression_test.cpp), with
// Debian's libdraco and libmeshoptimizer encoders: a small mesh, its uncompressed glTF, its
// KHR_draco_mesh_compression glTF and its EXT_/KHR_meshopt_compression glTF, each as JSON (to
// vary) and the bytes of its one binary buffer.

#include <draco/compression/decode.h>
#include <draco/compression/encode.h>
#include <draco/mesh/triangle_soup_mesh_builder.h>
#include <gtest/gtest.h>
#include <meshoptimizer.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <nlohmann/json.hpp>
#include <numbers>
#include <string>
#include <vector>

namespace glint::test {

/// A mesh as a glTF file holds it: texture coordinates with v down the image.
struct TestMesh {
    std::vector<std::array<float, 3>> positions, normals;
    std::vector<std::array<float, 2>> uvs;
    std::vector<uint32_t> indices;  ///< Triangles, counter-clockwise.
};

/// A cube of side 2 about the origin: 4 vertices per face, each with its face's normal.
inline TestMesh cubeMesh() {
    TestMesh m;
    const int axes[6][3] = {{0, 1, 2}, {0, 1, 2}, {1, 2, 0}, {1, 2, 0}, {2, 0, 1}, {2, 0, 1}};
    for (int f = 0; f < 6; ++f) {
        const float s = f % 2 == 0 ? 1.0f : -1.0f;
        const int n = axes[f][2], u = axes[f][0], v = axes[f][1];
        const uint32_t first = static_cast<uint32_t>(m.positions.size());
        const float corners[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
        for (const auto& c : corners) {
            std::array<float, 3> p{}, normal{};
            p[static_cast<size_t>(n)] = s;
            p[static_cast<size_t>(u)] = c[0] * s;  // mirrored on the negative faces: CCW outside
            p[static_cast<size_t>(v)] = c[1];
            normal[static_cast<size_t>(n)] = s;
            m.positions.push_back(p);
            m.normals.push_back(normal);
            m.uvs.push_back({(c[0] + 1) / 2, (1 - c[1]) / 2});
        }
        for (uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) m.indices.push_back(first + i);
    }
    return m;
}

/// A UV sphere of radius 1 (`rings` x `segments` cells, triangles at the poles), smooth normals.
inline TestMesh sphereMesh(int rings, int segments) {
    TestMesh m;
    const double pi = std::numbers::pi;
    for (int r = 0; r <= rings; ++r)
        for (int s = 0; s <= segments; ++s) {
            const double theta = pi * r / rings, phi = 2 * pi * s / segments;
            const std::array<float, 3> p = {float(std::sin(theta) * std::cos(phi)),
                                            float(std::cos(theta)),
                                            float(-std::sin(theta) * std::sin(phi))};
            m.positions.push_back(p);
            m.normals.push_back(p);
            m.uvs.push_back({float(s) / float(segments), float(r) / float(rings)});
        }
    const uint32_t row = static_cast<uint32_t>(segments + 1);
    for (uint32_t r = 0; r < uint32_t(rings); ++r)
        for (uint32_t s = 0; s < uint32_t(segments); ++s) {
            const uint32_t a = r * row + s, b = a + row;
            // The triangles with two corners at a pole have no area: left out.
            if (r + 1 < uint32_t(rings)) m.indices.insert(m.indices.end(), {a, b, b + 1});
            if (r > 0) m.indices.insert(m.indices.end(), {a, b + 1, a + 1});
        }
    return m;
}

/// The bytes of one glTF buffer, built piece by piece, each piece aligned to 4 bytes.
struct BinaryBuffer {
    std::string bytes;
    /// Appends `size` bytes at `data`; returns their offset.
    size_t add(const void* data, size_t size) {
        bytes.append((4 - bytes.size() % 4) % 4, '\0');
        const size_t at = bytes.size();
        bytes.append(static_cast<const char*>(data), size);
        return at;
    }
    template <typename T>
    size_t add(const std::vector<T>& v) {
        return add(v.data(), v.size() * sizeof(T));
    }
};

/// An asset: its JSON and the bytes of buffer 0 (the .glb's chunk, or a .bin beside a .gltf).
struct TestAsset {
    nlohmann::json json;
    std::string bin;
};

/// The skeleton every asset shares: one mesh of one primitive, placed by one node.
inline nlohmann::json assetSkeleton() {
    nlohmann::json j;
    j["asset"] = {{"version", "2.0"}};
    j["scene"] = 0;
    j["scenes"] = nlohmann::json::array({{{"nodes", {0}}}});
    j["nodes"] = nlohmann::json::array({{{"mesh", 0}}});
    j["meshes"] = nlohmann::json::array({{{"primitives", nlohmann::json::array({{}})}}});
    return j;
}

inline nlohmann::json& primitiveOf(TestAsset& a) { return a.json["meshes"][0]["primitives"][0]; }

inline nlohmann::json accessorJson(int componentType, size_t count, const char* type) {
    return {{"componentType", componentType}, {"count", count}, {"type", type}};
}

/// `m` as a plain glTF: float attributes and 32-bit indices in buffer 0.
inline TestAsset plainAsset(const TestMesh& m) {
    TestAsset a;
    a.json = assetSkeleton();
    BinaryBuffer bin;
    auto view = [&](size_t offset, size_t length) {
        a.json["bufferViews"].push_back(
            {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", length}});
        return a.json["bufferViews"].size() - 1;
    };
    auto accessor = [&](size_t v, int type, size_t count, const char* kind) {
        nlohmann::json acc = accessorJson(type, count, kind);
        acc["bufferView"] = v;
        a.json["accessors"].push_back(acc);
        return a.json["accessors"].size() - 1;
    };
    const size_t n = m.positions.size();
    nlohmann::json& p = primitiveOf(a);
    p["indices"] =
        accessor(view(bin.add(m.indices), m.indices.size() * 4), 5125, m.indices.size(), "SCALAR");
    p["attributes"]["POSITION"] = accessor(view(bin.add(m.positions), n * 12), 5126, n, "VEC3");
    p["attributes"]["NORMAL"] = accessor(view(bin.add(m.normals), n * 12), 5126, n, "VEC3");
    p["attributes"]["TEXCOORD_0"] = accessor(view(bin.add(m.uvs), n * 8), 5126, n, "VEC2");
    a.bin = bin.bytes;
    a.json["buffers"] = nlohmann::json::array({{{"byteLength", a.bin.size()}}});
    return a;
}

struct DracoSettings {
    int speed = 5;         ///< libdraco's encoding speed: 10 is sequential, below edgebreaker.
    int indexType = 5123;  ///< The indices accessor's component type.
    int positionBits = 14, normalBits = 10, uvBits = 12;  ///< Quantization (0: none)
    /// COLOR_0 (bytes), TANGENT (floats) and TEXCOORD_1 (floats in Draco, unsigned shorts in
    /// its accessor) too, made from each vertex by the functions below.
    bool otherAttributes = false;
};

/// The other attributes of vertex `i` of a mesh.
inline std::array<uint8_t, 4> testColor(size_t i) {
    return {uint8_t(10 * i % 256), uint8_t(255 - 7 * i % 256), 128, 255};
}
inline std::array<float, 4> testTangent(size_t i) {
    const float a = 0.3f * float(i);
    return {std::cos(a), std::sin(a), 0, i % 2 ? 1.0f : -1.0f};
}
inline std::array<float, 2> testUv1(const TestMesh& m, size_t i) {
    return {m.uvs[i][0] * 0.5f, m.uvs[i][1] * 0.5f + 0.25f};
}

/// `m` compressed with libdraco into a KHR_draco_mesh_compression asset, written as a tool
/// does: the accessors declare what the decoded mesh holds (its points and triangles, found
/// by decoding it) and have no bufferView.
inline TestAsset dracoAsset(const TestMesh& m, const DracoSettings& settings = {}) {
    draco::TriangleSoupMeshBuilder builder;
    const int faces = static_cast<int>(m.indices.size() / 3);
    builder.Start(faces);
    const int pos = builder.AddAttribute(draco::GeometryAttribute::POSITION, 3, draco::DT_FLOAT32);
    const int nor = builder.AddAttribute(draco::GeometryAttribute::NORMAL, 3, draco::DT_FLOAT32);
    const int tex = builder.AddAttribute(draco::GeometryAttribute::TEX_COORD, 2, draco::DT_FLOAT32);
    int col = -1, tan = -1, tex1 = -1;
    if (settings.otherAttributes) {
        col = builder.AddAttribute(draco::GeometryAttribute::COLOR, 4, draco::DT_UINT8, true);
        tan = builder.AddAttribute(draco::GeometryAttribute::GENERIC, 4, draco::DT_FLOAT32);
        tex1 = builder.AddAttribute(draco::GeometryAttribute::TEX_COORD, 2, draco::DT_FLOAT32);
    }
    for (int f = 0; f < faces; ++f) {
        const uint32_t* t = &m.indices[static_cast<size_t>(3 * f)];
        const draco::FaceIndex face(static_cast<uint32_t>(f));
        if (settings.otherAttributes) {
            std::array<std::array<uint8_t, 4>, 3> c;
            std::array<std::array<float, 4>, 3> g;
            std::array<std::array<float, 2>, 3> u;
            for (size_t k = 0; k < 3; ++k)
                c[k] = testColor(t[k]), g[k] = testTangent(t[k]), u[k] = testUv1(m, t[k]);
            builder.SetAttributeValuesForFace(col, face, c[0].data(), c[1].data(), c[2].data());
            builder.SetAttributeValuesForFace(tan, face, g[0].data(), g[1].data(), g[2].data());
            builder.SetAttributeValuesForFace(tex1, face, u[0].data(), u[1].data(), u[2].data());
        }
        builder.SetAttributeValuesForFace(pos, face, m.positions[t[0]].data(),
                                          m.positions[t[1]].data(), m.positions[t[2]].data());
        builder.SetAttributeValuesForFace(nor, face, m.normals[t[0]].data(), m.normals[t[1]].data(),
                                          m.normals[t[2]].data());
        builder.SetAttributeValuesForFace(tex, face, m.uvs[t[0]].data(), m.uvs[t[1]].data(),
                                          m.uvs[t[2]].data());
    }
    std::unique_ptr<draco::Mesh> mesh = builder.Finalize();
    EXPECT_TRUE(mesh);
    draco::Encoder encoder;
    encoder.SetSpeedOptions(settings.speed, settings.speed);
    if (settings.positionBits)
        encoder.SetAttributeQuantization(draco::GeometryAttribute::POSITION, settings.positionBits);
    if (settings.normalBits)
        encoder.SetAttributeQuantization(draco::GeometryAttribute::NORMAL, settings.normalBits);
    if (settings.uvBits)
        encoder.SetAttributeQuantization(draco::GeometryAttribute::TEX_COORD, settings.uvBits);
    draco::EncoderBuffer encoded;
    EXPECT_TRUE(encoder.EncodeMeshToBuffer(*mesh, &encoded).ok());

    // What a decoder will find: the accessors' counts.
    draco::DecoderBuffer in;
    in.Init(encoded.data(), encoded.size());
    draco::Decoder decoder;
    auto decoded = decoder.DecodeMeshFromBuffer(&in);
    EXPECT_TRUE(decoded.ok());
    const size_t points = decoded.value()->num_points();
    const size_t triangles = decoded.value()->num_faces();

    TestAsset a;
    a.json = assetSkeleton();
    a.json["extensionsUsed"] = {"KHR_draco_mesh_compression"};
    a.json["extensionsRequired"] = {"KHR_draco_mesh_compression"};
    a.bin.assign(encoded.data(), encoded.size());
    a.json["buffers"] = nlohmann::json::array({{{"byteLength", a.bin.size()}}});
    a.json["bufferViews"] = nlohmann::json::array({{{"buffer", 0}, {"byteLength", a.bin.size()}}});
    a.json["accessors"] = {accessorJson(settings.indexType, 3 * triangles, "SCALAR"),
                           accessorJson(5126, points, "VEC3"), accessorJson(5126, points, "VEC3"),
                           accessorJson(5126, points, "VEC2")};
    nlohmann::json& p = primitiveOf(a);
    p["indices"] = 0;
    p["attributes"] = {{"POSITION", 1}, {"NORMAL", 2}, {"TEXCOORD_0", 3}};
    p["extensions"]["KHR_draco_mesh_compression"] = {
        {"bufferView", 0},
        {"attributes",
         {{"POSITION", mesh->attribute(pos)->unique_id()},
          {"NORMAL", mesh->attribute(nor)->unique_id()},
          {"TEXCOORD_0", mesh->attribute(tex)->unique_id()}}}};
    if (settings.otherAttributes) {
        nlohmann::json color = accessorJson(5121, points, "VEC4"),
                       uv1 = accessorJson(5123, points, "VEC2");
        color["normalized"] = uv1["normalized"] = true;
        a.json["accessors"].push_back(color);                               // 4
        a.json["accessors"].push_back(accessorJson(5126, points, "VEC4"));  // 5
        a.json["accessors"].push_back(uv1);                                 // 6
        p["attributes"]["COLOR_0"] = 4;
        p["attributes"]["TANGENT"] = 5;
        p["attributes"]["TEXCOORD_1"] = 6;
        auto& ids = p["extensions"]["KHR_draco_mesh_compression"]["attributes"];
        ids["COLOR_0"] = mesh->attribute(col)->unique_id();
        ids["TANGENT"] = mesh->attribute(tan)->unique_id();
        ids["TEXCOORD_1"] = mesh->attribute(tex1)->unique_id();
    }
    return a;
}

struct MeshoptSettings {
    const char* extension = "EXT_meshopt_compression";
    bool octahedralNormals = true;      ///< NORMAL as 8-bit octahedral (4-byte stride), else float
    bool exponentialPositions = false;  ///< POSITION through the EXPONENTIAL filter
    bool indexSequence = false;         ///< indices in INDICES mode, else TRIANGLES
    int indexBytes = 2;
    bool fallbackFlag = true;  ///< the fallback buffer says so
};

/// `m` compressed with libmeshoptimizer into a meshopt asset as gltfpack writes one: the
/// compressed data in buffer 0, the bufferViews in buffer 1, a fallback buffer with no data.
inline TestAsset meshoptAsset(const TestMesh& m, const MeshoptSettings& s = {}) {
    TestAsset a;
    a.json = assetSkeleton();
    a.json["extensionsUsed"] = {s.extension, "KHR_mesh_quantization"};
    a.json["extensionsRequired"] = {s.extension, "KHR_mesh_quantization"};
    BinaryBuffer compressed;
    size_t fallbackSize = 0;
    // One bufferView holding `count` elements of `stride` bytes, compressed as `mode`.
    auto view = [&](const std::string& encoded, size_t count, size_t stride, const char* mode,
                    const char* filter, bool vertexView) {
        fallbackSize = (fallbackSize + 3) / 4 * 4;
        nlohmann::json ext = {{"buffer", 0},
                              {"byteOffset", compressed.add(encoded.data(), encoded.size())},
                              {"byteLength", encoded.size()},
                              {"byteStride", stride},
                              {"count", count},
                              {"mode", mode}};
        if (filter) ext["filter"] = filter;
        nlohmann::json v = {{"buffer", 1},
                            {"byteOffset", fallbackSize},
                            {"byteLength", count * stride},
                            {"extensions", {{s.extension, ext}}}};
        if (vertexView) v["byteStride"] = stride;
        fallbackSize += count * stride;
        a.json["bufferViews"].push_back(v);
        return a.json["bufferViews"].size() - 1;
    };
    auto vertices = [&](const void* data, size_t count, size_t stride) {
        std::string out(meshopt_encodeVertexBufferBound(count, stride), '\0');
        out.resize(meshopt_encodeVertexBuffer(reinterpret_cast<unsigned char*>(out.data()),
                                              out.size(), data, count, stride));
        return out;
    };
    auto accessor = [&](size_t v, int type, size_t count, const char* kind, bool normalized) {
        nlohmann::json acc = accessorJson(type, count, kind);
        acc["bufferView"] = v;
        if (normalized) acc["normalized"] = true;
        a.json["accessors"].push_back(acc);
        return a.json["accessors"].size() - 1;
    };
    const size_t n = m.positions.size();
    nlohmann::json& p = primitiveOf(a);

    std::string indices(std::max(meshopt_encodeIndexBufferBound(m.indices.size(), n),
                                 meshopt_encodeIndexSequenceBound(m.indices.size(), n)),
                        '\0');
    auto* out = reinterpret_cast<unsigned char*>(indices.data());
    indices.resize(
        s.indexSequence
            ? meshopt_encodeIndexSequence(out, indices.size(), m.indices.data(), m.indices.size())
            : meshopt_encodeIndexBuffer(out, indices.size(), m.indices.data(), m.indices.size()));
    p["indices"] = accessor(view(indices, m.indices.size(), size_t(s.indexBytes),
                                 s.indexSequence ? "INDICES" : "TRIANGLES", nullptr, false),
                            s.indexBytes == 2 ? 5123 : 5125, m.indices.size(), "SCALAR", false);

    if (s.exponentialPositions) {
        std::vector<uint32_t> filtered(n * 3);
        meshopt_encodeFilterExp(filtered.data(), n, 12, 18, &m.positions[0][0]);
        p["attributes"]["POSITION"] = accessor(
            view(vertices(filtered.data(), n, 12), n, 12, "ATTRIBUTES", "EXPONENTIAL", true), 5126,
            n, "VEC3", false);
    } else {
        p["attributes"]["POSITION"] =
            accessor(view(vertices(m.positions.data(), n, 12), n, 12, "ATTRIBUTES", nullptr, true),
                     5126, n, "VEC3", false);
    }
    if (s.octahedralNormals) {
        std::vector<float> normals4;
        for (const auto& v : m.normals) normals4.insert(normals4.end(), {v[0], v[1], v[2], 0});
        std::vector<int8_t> oct(n * 4);
        meshopt_encodeFilterOct(oct.data(), n, 4, 8, normals4.data());
        p["attributes"]["NORMAL"] =
            accessor(view(vertices(oct.data(), n, 4), n, 4, "ATTRIBUTES", "OCTAHEDRAL", true), 5120,
                     n, "VEC3", true);
    } else {
        p["attributes"]["NORMAL"] =
            accessor(view(vertices(m.normals.data(), n, 12), n, 12, "ATTRIBUTES", nullptr, true),
                     5126, n, "VEC3", false);
    }
    p["attributes"]["TEXCOORD_0"] =
        accessor(view(vertices(m.uvs.data(), n, 8), n, 8, "ATTRIBUTES", nullptr, true), 5126, n,
                 "VEC2", false);

    a.bin = compressed.bytes;
    nlohmann::json fallback = {{"byteLength", fallbackSize}};
    if (s.fallbackFlag) fallback["extensions"][s.extension] = {{"fallback", true}};
    a.json["buffers"] = nlohmann::json::array({{{"byteLength", a.bin.size()}}, fallback});
    return a;
}

}  // namespace glint::test
