// Compressed glTF meshes (io/gltf/gltf_compression.cpp): KHR_draco_mesh_compression and
// EXT_/KHR_meshopt_compression files written here with Debian's libdraco and libmeshoptimizer
// (gltf_compression_support.h) load as their uncompressed originals do, within the encoders'
// quantization, and render alike; broken ones are errors that name the extension.

#include <dlfcn.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <stb_image.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>

#include "glint/io/gltf/gltf_internal.h"
#include "glint/io/gltf/gltf_loader.h"
#include "glint/render/renderer.h"
#include "glint/scene/model_framing.h"
#include "unit/io/gltf/gltf_compression_support.h"
#include "unit/io/gltf/gltf_test_support.h"
#include "unit/test_support.h"

namespace glint {
namespace {

using namespace glint::test;
using ::testing::AllOf;
using ::testing::HasSubstr;

Model loadAsset(const TestAsset& a, std::vector<Diagnostic>* warnings = nullptr,
                const GltfOptions& options = {}) {
    std::vector<Diagnostic> w;
    Model m = parseGltf(glbOf(a.json.dump(), a.bin), "t.glb", w, options);
    if (warnings)
        *warnings = w;
    else
        EXPECT_TRUE(w.empty()) << w.front().format("warning");
    return m;
}

/// The error loading `a` gives (a test failure if it loads).
std::string errorOf(const TestAsset& a, const GltfOptions& options = {}) {
    std::vector<Diagnostic> warnings;
    try {
        parseGltf(glbOf(a.json.dump(), a.bin), "t.glb", warnings, options);
    } catch (const SceneError& e) {
        return e.diagnostic().message;
    }
    ADD_FAILURE() << "no SceneError for " << a.json.dump();
    return {};
}

/// A triangle corner as glTF holds it: position, normal, uv (v down).
struct Vertex {
    std::array<double, 3> p, n;
    std::array<double, 2> uv;
};

std::vector<std::array<Vertex, 3>> trianglesOf(const TestMesh& m) {
    std::vector<std::array<Vertex, 3>> out;
    for (size_t t = 0; t + 2 < m.indices.size(); t += 3) {
        std::array<Vertex, 3> tri;
        for (size_t k = 0; k < 3; ++k) {
            const uint32_t i = m.indices[t + k];
            tri[k] = {{m.positions[i][0], m.positions[i][1], m.positions[i][2]},
                      {m.normals[i][0], m.normals[i][1], m.normals[i][2]},
                      {m.uvs[i][0], m.uvs[i][1]}};
        }
        out.push_back(tri);
    }
    return out;
}

std::vector<std::array<Vertex, 3>> trianglesOf(const MeshData& m) {
    std::vector<std::array<Vertex, 3>> out;
    for (const MeshData::Triangle& t : m.triangles) {
        std::array<Vertex, 3> tri;
        for (size_t k = 0; k < 3; ++k) {
            const MeshData::Corner& c = t.corners[k];
            const Vec3f p = m.positions[c.position];
            EXPECT_NE(c.normal, MeshData::kNone);
            EXPECT_NE(c.uv, MeshData::kNone);
            const Vec3f n = c.normal == MeshData::kNone ? Vec3f() : m.normals[c.normal];
            const TexCoord uv = c.uv == MeshData::kNone ? TexCoord{} : m.uvs[c.uv];
            tri[k] = {{p.x, p.y, p.z}, {n.x, n.y, n.z}, {uv[0], 1.0 - uv[1]}};  // v down again
        }
        out.push_back(tri);
    }
    return out;
}

struct Tolerance {
    double position, normal, uv;
};

double largestDifference(const Vertex& a, const Vertex& b, const Tolerance& tol) {
    double worst = 0;
    for (size_t i = 0; i < 3; ++i) {
        worst = std::max(worst, std::abs(a.p[i] - b.p[i]) / tol.position);
        worst = std::max(worst, std::abs(a.n[i] - b.n[i]) / tol.normal);
    }
    for (size_t i = 0; i < 2; ++i) worst = std::max(worst, std::abs(a.uv[i] - b.uv[i]) / tol.uv);
    return worst;
}

/// How many triangles of `got` are not those of `want` (in any order and each turned any way
/// that keeps its winding, every value within `tol`); all of them if the counts differ.
size_t unmatchedTriangles(const MeshData& got, const TestMesh& want, const Tolerance& tol) {
    auto a = trianglesOf(got), b = trianglesOf(want);
    if (a.size() != b.size()) return std::max(a.size(), b.size());
    std::vector<bool> used(b.size());
    size_t unmatched = 0;
    for (const auto& t : a) {
        size_t best = b.size();
        for (size_t j = 0; j < b.size() && best == b.size(); ++j) {
            if (used[j]) continue;
            for (size_t turn = 0; turn < 3; ++turn) {
                double worst = 0;
                for (size_t k = 0; k < 3; ++k)
                    worst = std::max(worst, largestDifference(t[k], b[j][(k + turn) % 3], tol));
                if (worst <= 1) best = j;
            }
        }
        if (best == b.size())
            ++unmatched;
        else
            used[best] = true;
    }
    return unmatched;
}

/// Half a quantization step over `range` with `bits` (exact when 0), and float rounding.
double halfStep(double range, int bits) {
    return (bits ? range / ((1 << bits) - 1) / 2 : 0) + 1e-6;
}

TEST(GltfDraco, RoundTripsWithinTheQuantization) {
    struct Case {
        const char* name;
        TestMesh mesh;
        DracoSettings settings;
    };
    DracoSettings sequential, lossless, bytes, ints;
    sequential.speed = 10;
    lossless.positionBits = lossless.normalBits = lossless.uvBits = 0;
    bytes.indexType = 5121;
    ints.indexType = 5125;
    const std::vector<Case> cases = {{"cube, edgebreaker", cubeMesh(), {}},
                                     {"cube, sequential", cubeMesh(), sequential},
                                     {"cube, byte indices", cubeMesh(), bytes},
                                     {"sphere, edgebreaker", sphereMesh(12, 16), {}},
                                     {"sphere, int indices", sphereMesh(12, 16), ints},
                                     {"sphere, sequential", sphereMesh(12, 16), sequential},
                                     {"sphere, lossless", sphereMesh(12, 16), lossless}};
    for (const Case& c : cases) {
        SCOPED_TRACE(c.name);
        Model model = loadAsset(dracoAsset(c.mesh, c.settings));
        ASSERT_EQ(model.meshes.size(), 1u);
        // Draco's octahedral normals: about 2 / 2^bits per component.
        const double normal =
            c.settings.normalBits ? 4.0 / (1 << c.settings.normalBits) + 1e-6 : 1e-6;
        EXPECT_EQ(unmatchedTriangles(model.meshes[0], c.mesh,
                                     {halfStep(2, c.settings.positionBits), normal,
                                      halfStep(1, c.settings.uvBits)}),
                  0u);
    }
}

TEST(GltfDraco, EveryAttributeItListsDecodesIntoItsAccessorsLayout) {
    // COLOR_0 as normalised bytes, TANGENT as floats and TEXCOORD_1 as normalised unsigned
    // shorts (from Draco's floats: scaled and rounded), read as the meshes code reads any
    // accessor: through the loader's own hook, by point, matched to the cube's vertices by
    // position and normal.
    const TestMesh cube = cubeMesh();
    DracoSettings settings;
    settings.otherAttributes = true;
    const TestAsset a = dracoAsset(cube, settings);
    std::vector<Diagnostic> warnings;
    GltfOptions options;
    gltf::Context ctx("t.glb", warnings, options);
    gltf::parseContainer(ctx, glbOf(a.json.dump(), a.bin));
    const auto* positions = gltf::dracoAccessor(ctx, 1);
    const auto* normals = gltf::dracoAccessor(ctx, 2);
    const auto* colors = gltf::dracoAccessor(ctx, 4);
    const auto* tangents = gltf::dracoAccessor(ctx, 5);
    const auto* uv1s = gltf::dracoAccessor(ctx, 6);
    ASSERT_TRUE(positions && normals && colors && tangents && uv1s);
    const size_t points = positions->size() / 12;
    ASSERT_EQ(points, 24u);
    ASSERT_EQ(colors->size(), points * 4);
    ASSERT_EQ(tangents->size(), points * 16);
    ASSERT_EQ(uv1s->size(), points * 4);
    for (size_t i = 0; i < points; ++i) {
        float p[3], n[3], t[4];
        uint16_t uv1[2];
        std::memcpy(p, positions->data() + 12 * i, 12);
        std::memcpy(n, normals->data() + 12 * i, 12);
        std::memcpy(t, tangents->data() + 16 * i, 16);
        std::memcpy(uv1, uv1s->data() + 4 * i, 4);
        size_t v = cube.positions.size();
        for (size_t k = 0; k < cube.positions.size(); ++k) {
            double d = 0;
            for (size_t c = 0; c < 3; ++c)
                d += std::abs(p[c] - cube.positions[k][c]) + std::abs(n[c] - cube.normals[k][c]);
            if (d < 0.01) v = k;
        }
        ASSERT_LT(v, cube.positions.size()) << "point " << i;
        const auto color = testColor(v);
        const auto tangent = testTangent(v);
        const auto uv = testUv1(cube, v);
        for (size_t c = 0; c < 4; ++c) {
            EXPECT_EQ((*colors)[4 * i + c], color[c]);
            EXPECT_FLOAT_EQ(t[c], tangent[c]);
        }
        for (size_t c = 0; c < 2; ++c)
            EXPECT_NEAR(uv1[c], uv[c] * 65535.0, 65535.0 * halfStep(1, 12) + 0.5);
    }
    // And the mesh loads with them.
    Model model = loadAsset(a);
    EXPECT_EQ(model.meshes[0].triangles.size(), 12u);
}

TEST(GltfDraco, TheComparisonTellsMeshesApart) {
    // The check above tells meshes apart: the cube is not the cube moved by a quantization step.
    TestMesh moved = cubeMesh();
    for (auto& p : moved.positions) p[0] += 3e-4f;
    Model model = loadAsset(dracoAsset(cubeMesh()));
    const Tolerance tol{halfStep(2, 14), 4.0 / 1024 + 1e-6, halfStep(1, 12)};
    EXPECT_EQ(unmatchedTriangles(model.meshes[0], cubeMesh(), tol), 0u);
    EXPECT_EQ(unmatchedTriangles(model.meshes[0], moved, tol), 12u);
}

using GltfCompressionFiles = TempDirTest;

TEST_F(GltfCompressionFiles, DracoFromAnExternalBufferFile) {
    TestAsset a = dracoAsset(sphereMesh(6, 8));
    a.json["buffers"][0]["uri"] = "sphere.bin";
    std::ofstream(path("sphere.bin"), std::ios::binary) << a.bin;
    std::ofstream(path("sphere.gltf")) << a.json.dump(1);
    std::vector<Diagnostic> warnings;
    Model model = loadGltf(path("sphere.gltf"), warnings);
    EXPECT_TRUE(warnings.empty());
    ASSERT_EQ(model.meshes.size(), 1u);
    EXPECT_EQ(unmatchedTriangles(model.meshes[0], sphereMesh(6, 8),
                                 {halfStep(2, 14), 4.0 / 1024 + 1e-6, halfStep(1, 12)}),
              0u);
}

TEST_F(GltfCompressionFiles, MeshoptFallbackBufferFileIsNeverRead) {
    // The fallback names a file that does not exist: its data is not needed.
    TestAsset a = meshoptAsset(cubeMesh());
    a.json["buffers"][0]["uri"] = "cube.bin";
    a.json["buffers"][1]["uri"] = "missing-fallback.bin";
    std::ofstream(path("cube.bin"), std::ios::binary) << a.bin;
    std::ofstream(path("cube.gltf")) << a.json.dump(1);
    std::vector<Diagnostic> warnings;
    Model model = loadGltf(path("cube.gltf"), warnings);
    EXPECT_TRUE(warnings.empty());
    ASSERT_EQ(model.meshes.size(), 1u);
    EXPECT_EQ(unmatchedTriangles(model.meshes[0], cubeMesh(), {1e-6, 2.0 / 127, 1e-6}), 0u);
    // Without the fallback flag, a buffer with a URI is an ordinary one, and is read.
    a.json["buffers"][1].erase("extensions");
    std::ofstream(path("cube.gltf")) << a.json.dump(1);
    EXPECT_THROW(loadGltf(path("cube.gltf"), warnings), SceneError);
}

TEST(GltfMeshopt, RoundTripsExactlyOrWithinTheFilters) {
    struct Case {
        const char* name;
        MeshoptSettings settings;
        Tolerance tol;
    };
    MeshoptSettings floats, exponential, sequence, ints, unflagged, khr;
    floats.octahedralNormals = false;
    exponential.exponentialPositions = true;
    sequence.indexSequence = true;
    ints.indexBytes = 4;
    unflagged.fallbackFlag = false;
    khr.extension = "KHR_meshopt_compression";
    const double oct = 2.0 / 127;  // 8-bit octahedral normals
    const std::vector<Case> cases = {
        {"float attributes", floats, {1e-6, 1e-6, 1e-6}},
        {"octahedral normals", {}, {1e-6, oct, 1e-6}},
        {"exponential positions", exponential, {2e-5, oct, 1e-6}},
        {"INDICES mode", sequence, {1e-6, oct, 1e-6}},
        {"32-bit indices", ints, {1e-6, oct, 1e-6}},
        {"placeholder without the fallback flag", unflagged, {1e-6, oct, 1e-6}},
        {"KHR_meshopt_compression", khr, {1e-6, oct, 1e-6}},
    };
    for (const TestMesh& mesh : {cubeMesh(), sphereMesh(12, 16)})
        for (const Case& c : cases) {
            SCOPED_TRACE(std::string(c.name) + ", " + std::to_string(mesh.indices.size()));
            Model model = loadAsset(meshoptAsset(mesh, c.settings));
            ASSERT_EQ(model.meshes.size(), 1u);
            EXPECT_EQ(unmatchedTriangles(model.meshes[0], mesh, c.tol), 0u);
            // meshopt keeps the triangles' order.
            ASSERT_EQ(model.meshes[0].triangles.size(), mesh.indices.size() / 3);
            const Vec3f first =
                model.meshes[0].positions[model.meshes[0].triangles[5].corners[0].position];
            const std::array<Vertex, 3> want = trianglesOf(mesh)[5];
            const bool found = std::any_of(want.begin(), want.end(), [&](const Vertex& v) {
                return std::abs(v.p[0] - first.x) + std::abs(v.p[1] - first.y) +
                           std::abs(v.p[2] - first.z) <=
                       3 * c.tol.position;
            });
            EXPECT_TRUE(found);
        }
}

/// `model` framed as `glint model.glb` frames it, rendered at 64 x 48.
Film renderModel(const Model& model) {
    ModelScene m = frameModelScene(model, 64, 48);
    m.scene->prepare();
    RenderOptions o;
    o.threads = 1;
    return render(*m.scene, o).film;
}

/// Mean absolute difference of two films' pixels, over the channels.
double meanDifference(const Film& a, const Film& b) {
    double sum = 0;
    for (int y = 0; y < a.height(); ++y)
        for (int x = 0; x < a.width(); ++x) {
            const Vec3 d = a.at(x, y) - b.at(x, y);
            sum += (std::abs(d.x) + std::abs(d.y) + std::abs(d.z)) / 3;
        }
    return sum / (a.width() * a.height());
}

TEST(GltfCompression, CompressedMeshesRenderAsTheUncompressedOnes) {
    // Turned so that three faces of the cube show.
    auto turned = [](TestAsset a) {
        a.json["nodes"][0]["rotation"] = {0.2798, 0.3647, 0.1160, 0.8805};
        return a;
    };
    const TestMesh cube = cubeMesh(), sphere = sphereMesh(12, 16);
    const Film plainCube = renderModel(loadAsset(turned(plainAsset(cube))));
    const Film plainSphere = renderModel(loadAsset(turned(plainAsset(sphere))));
    ASSERT_EQ(plainCube.width(), 64);
    // The cube's values survive the encoders exactly, or nearly.
    EXPECT_LT(meanDifference(plainCube, renderModel(loadAsset(turned(dracoAsset(cube))))), 1e-4);
    EXPECT_LT(meanDifference(plainCube, renderModel(loadAsset(turned(meshoptAsset(cube))))), 1e-4);
    // The sphere's smooth normals are quantized (10 bits for Draco, 8 for meshopt's octahedral
    // filter): a little shading moves.
    const double draco =
        meanDifference(plainSphere, renderModel(loadAsset(turned(dracoAsset(sphere)))));
    const double meshopt =
        meanDifference(plainSphere, renderModel(loadAsset(turned(meshoptAsset(sphere)))));
    // (1e-3: shading normals that bend a direction across the surface now carry no light, which
    // moves a few more pixels at the sphere's rim with the quantized normals.)
    EXPECT_LT(draco, 1e-3);
    EXPECT_LT(meshopt, 1e-3);
    // Another shape differs by far more: the measure sees geometry.
    EXPECT_GT(meanDifference(plainCube, plainSphere), 1e-2);
}

// ---- errors ----

TEST(GltfDraco, TruncatedDataIsAnErrorNamingTheExtension) {
    const TestAsset a = dracoAsset(sphereMesh(8, 8));
    for (size_t keep : {size_t(1), size_t(8), a.bin.size() / 2, a.bin.size() - 1}) {
        SCOPED_TRACE(keep);
        TestAsset cut = a;
        cut.bin.resize(keep);
        cut.json["buffers"][0]["byteLength"] = keep;
        cut.json["bufferViews"][0]["byteLength"] = keep;
        EXPECT_THAT(errorOf(cut),
                    AllOf(HasSubstr("mesh 0, primitive 0: KHR_draco_mesh_compression"),
                          HasSubstr("libdraco cannot decode bufferView 0")));
    }
}

TEST(GltfDraco, CorruptDataNeverCrashes) {
    const TestAsset a = dracoAsset(sphereMesh(8, 8));
    std::mt19937 rng(12);
    int failed = 0, loaded = 0;
    for (int trial = 0; trial < 300; ++trial) {
        TestAsset bad = a;
        for (int k = 0; k < 1 + trial % 4; ++k)
            bad.bin[rng() % bad.bin.size()] = static_cast<char>(rng());
        std::vector<Diagnostic> warnings;
        try {
            parseGltf(glbOf(bad.json.dump(), bad.bin), "t.glb", warnings);
            ++loaded;
        } catch (const SceneError&) {
            ++failed;
        }
    }
    EXPECT_GT(failed, 0);
    EXPECT_EQ(failed + loaded, 300);
}

TEST(GltfDraco, AccessorsMustMatchTheDecodedMesh) {
    const TestAsset a = dracoAsset(cubeMesh());
    const std::string where = "mesh 0, primitive 0: KHR_draco_mesh_compression";
    TestAsset b = a;
    b.json["accessors"][1]["count"] = 25;
    EXPECT_THAT(errorOf(b), AllOf(HasSubstr(where), HasSubstr("accessor's count is 25, but the "
                                                              "decoded mesh has 24 points")));
    b = a;
    b.json["accessors"][0]["count"] = 35;
    EXPECT_THAT(errorOf(b), AllOf(HasSubstr(where), HasSubstr("accessor's count is 35, but the "
                                                              "decoded mesh has 12 triangles")));
    b = a;
    b.json["accessors"][3]["type"] = "VEC3";
    EXPECT_THAT(errorOf(b), AllOf(HasSubstr(where), HasSubstr("decoded attribute has 2 "
                                                              "components, the accessor 3")));
    b = a;
    b.json["accessors"][0]["componentType"] = 5126;
    EXPECT_THAT(errorOf(b), AllOf(HasSubstr(where), HasSubstr("indices must be unsigned")));
    b = a;
    b.json["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"]["attributes"]
          ["NORMAL"] = 7;
    EXPECT_THAT(errorOf(b), AllOf(HasSubstr(where), HasSubstr("no attribute of unique id 7")));
    b = a;
    b.json["meshes"][0]["primitives"][0]["attributes"].erase("TEXCOORD_0");
    EXPECT_THAT(errorOf(b), AllOf(HasSubstr(where), HasSubstr("names attribute TEXCOORD_0, which "
                                                              "the primitive does not have")));
    b = a;
    b.json["meshes"][0]["primitives"][0]["mode"] = 5;
    EXPECT_THAT(errorOf(b), AllOf(HasSubstr(where), HasSubstr("triangle lists")));
    b = a;
    b.json["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"].erase(
        "bufferView");
    EXPECT_THAT(errorOf(b), AllOf(HasSubstr("mesh 0, primitive 0: KHR_draco_mesh_compression"),
                                  HasSubstr("'bufferView' is required")));
    // A second primitive reading the same accessors from other Draco data.
    b = a;
    nlohmann::json second = b.json["meshes"][0]["primitives"][0];
    second["extensions"]["KHR_draco_mesh_compression"]["attributes"]["POSITION"] = 2;
    b.json["meshes"][0]["primitives"].push_back(second);
    EXPECT_THAT(errorOf(b), HasSubstr("is decoded from other Draco data"));
}

/// CPU seconds libdraco takes to decode `bytes`; negative if it cannot decode them.
double dracoDecodeSeconds(const std::string& bytes) {
    draco::DecoderBuffer in;
    in.Init(bytes.data(), bytes.size());
    draco::Decoder decoder;
    const std::clock_t start = std::clock();
    const bool ok = decoder.DecodeMeshFromBuffer(&in).ok();
    const double seconds = double(std::clock() - start) / CLOCKS_PER_SEC;
    return ok ? seconds : -1;
}

TEST(GltfDraco, CorruptDataThatMakesLibdracoSpinIsStopped) {
    // libdraco 1.5.5 loops over a count of texture-coordinate orientations it reads as it is
    // (docs/robustness.md). Find that count in the cube's data: the int32 that, made 2^25, makes
    // decoding slow (0.03 to 0.1 s; 2^31 takes seconds) but still successful. Speed 3
    // (draco_transcoder's default) predicts texture coordinates so.
    DracoSettings settings;
    settings.speed = 3;
    TestAsset a = dracoAsset(cubeMesh(), settings);
    const double normal = dracoDecodeSeconds(a.bin);
    std::string slow;
    for (size_t at = 11; at + 4 <= a.bin.size() && slow.empty(); ++at) {
        std::string patched = a.bin;
        const int32_t count = 1 << 25;
        std::memcpy(patched.data() + at, &count, 4);
        if (dracoDecodeSeconds(patched) > std::max(0.004, 30 * normal)) slow = patched;
    }
    ASSERT_FALSE(slow.empty()) << "libdraco no longer spins on a corrupt orientation count: "
                                  "update docs/robustness.md";
    a.bin = slow;
    // It still decodes, slowly: within the default allowance, but not within a tiny one.
    EXPECT_NO_THROW(loadAsset(a));
    GltfOptions strict;
    strict.dracoSeconds = 0.002;
    EXPECT_THAT(errorOf(a, strict),
                AllOf(HasSubstr("mesh 0, primitive 0: KHR_draco_mesh_compression: libdraco took"),
                      HasSubstr("far more than such data needs: the Draco data is corrupt")));
    // The cube as encoded decodes within the tiny allowance.
    EXPECT_NO_THROW(loadAsset(dracoAsset(cubeMesh(), settings), nullptr, strict));
}

TEST(GltfDraco, MemoryIsCheckedBeforeDecoding) {
    const TestAsset a = dracoAsset(sphereMesh(48, 64));
    GltfOptions small;
    small.limits.memoryBytes = 256 << 10;
    EXPECT_THAT(errorOf(a, small), AllOf(HasSubstr("KHR_draco_mesh_compression"),
                                         HasSubstr("decoding it needs about")));
    small.limits.memoryBytes = 64 << 20;
    EXPECT_NO_THROW(loadAsset(a, nullptr, small));
}

TEST(GltfMeshopt, CorruptOrTruncatedDataIsAnErrorNamingTheExtension) {
    const TestAsset a = meshoptAsset(sphereMesh(8, 8));
    // The POSITION view (1) loses its last bytes: its tail is not where it should be.
    TestAsset b = a;
    b.json["bufferViews"][1]["extensions"]["EXT_meshopt_compression"]["byteLength"] =
        b.json["bufferViews"][1]["extensions"]["EXT_meshopt_compression"]["byteLength"].get<int>() -
        20;
    EXPECT_THAT(errorOf(b),
                AllOf(HasSubstr("bufferView 1: EXT_meshopt_compression: its ATTRIBUTES data"),
                      HasSubstr("is corrupt")));
    // The index view (0) with a header byte of no codec.
    b = a;
    b.bin[b.json["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["byteOffset"]
              .get<size_t>()] = 0x42;
    EXPECT_THAT(errorOf(b), HasSubstr("bufferView 0: EXT_meshopt_compression: its TRIANGLES data"));
    // Random bytes anywhere: an error or a mesh, never a crash.
    std::mt19937 rng(5);
    int failed = 0;
    for (int trial = 0; trial < 300; ++trial) {
        b = a;
        for (int k = 0; k < 1 + trial % 4; ++k) b.bin[rng() % b.bin.size()] = char(rng());
        std::vector<Diagnostic> warnings;
        try {
            parseGltf(glbOf(b.json.dump(), b.bin), "t.glb", warnings);
        } catch (const SceneError&) {
            ++failed;
        }
    }
    EXPECT_GT(failed, 0);
}

TEST(GltfMeshopt, TheExtensionsRulesAreChecked) {
    const TestAsset a = meshoptAsset(cubeMesh());
    auto ext = [](TestAsset& t, int view) -> nlohmann::json& {
        return t.json["bufferViews"][view]["extensions"]["EXT_meshopt_compression"];
    };
    TestAsset b = a;
    ext(b, 1)["byteStride"] = 6;
    EXPECT_THAT(errorOf(b), HasSubstr("bufferView 1: EXT_meshopt_compression: byteStride must be "
                                      "a multiple of 4 from 4 to 256 for ATTRIBUTES, not 6"));
    b = a;
    ext(b, 1)["count"] = 23;
    EXPECT_THAT(errorOf(b), HasSubstr("count x byteStride (23 x 12) must be the bufferView's "
                                      "byteLength (288)"));
    b = a;
    ext(b, 0)["count"] = 35;
    EXPECT_THAT(errorOf(b), HasSubstr("count must be a multiple of 3 for TRIANGLES"));
    b = a;
    ext(b, 2)["filter"] = "QUATERNION";
    EXPECT_THAT(errorOf(b), HasSubstr("byteStride must be 8 for QUATERNION"));
    b = a;
    ext(b, 2)["filter"] = "COLOR";
    EXPECT_THAT(errorOf(b), HasSubstr("filter 'COLOR' is not NONE, OCTAHEDRAL, QUATERNION or "
                                      "EXPONENTIAL"));
    b = a;
    ext(b, 0)["mode"] = "STRIPS";
    EXPECT_THAT(errorOf(b), HasSubstr("mode 'STRIPS' is not ATTRIBUTES, TRIANGLES or INDICES"));
    b = a;
    ext(b, 1)["buffer"] = 1;
    EXPECT_THAT(errorOf(b), HasSubstr("its compressed data is in buffer 1, a fallback buffer"));
    // A count the compressed bytes cannot hold is refused before its memory is taken.
    b = a;
    ext(b, 1)["count"] = 100000000;
    b.json["bufferViews"][1]["byteLength"] = 1200000000;
    EXPECT_THAT(errorOf(b), HasSubstr("compressed bytes cannot hold 100000000 elements of 12 "
                                      "bytes"));
    b = a;
    ext(b, 1).erase("count");
    EXPECT_THAT(errorOf(b), HasSubstr("bufferView 1: EXT_meshopt_compression: 'count' is "
                                      "required"));
    // A view without compression in the fallback buffer.
    b = a;
    b.json["bufferViews"][2].erase("extensions");
    EXPECT_THAT(errorOf(b), HasSubstr("bufferView 2 refers to buffer 1, a meshopt fallback "
                                      "buffer, but has no meshopt compression"));
    b = a;
    ext(b, 2)["filter"] = "NONE";
    b.json["bufferViews"][2]["extensions"]["KHR_meshopt_compression"] = ext(b, 2);
    EXPECT_THAT(errorOf(b), HasSubstr("EXT_meshopt_compression and KHR_meshopt_compression "
                                      "exclude each other"));
}

TEST(GltfMeshopt, WhatDebiansLibraryCannotDecodeIsNamed) {
    MeshoptSettings khr;
    khr.extension = "KHR_meshopt_compression";
    const TestAsset a = meshoptAsset(cubeMesh(), khr);
    auto ext = [](TestAsset& t, int view) -> nlohmann::json& {
        return t.json["bufferViews"][view]["extensions"]["KHR_meshopt_compression"];
    };
    TestAsset b = a;
    ext(b, 2)["filter"] = "COLOR";
    EXPECT_THAT(errorOf(b), HasSubstr("bufferView 2: KHR_meshopt_compression: filter COLOR is not "
                                      "supported"));
    // Version 1 of the attribute codec (header 0xa1), which libmeshoptimizer 0.18 predates.
    b = a;
    b.bin[ext(b, 1)["byteOffset"].get<size_t>()] = char(0xa1);
    EXPECT_THAT(errorOf(b), HasSubstr("bufferView 1: KHR_meshopt_compression: its data is in "
                                      "version 1 of the attribute codec"));
}

TEST(GltfCompression, AnUnsupportedRequiredExtensionIsNamed) {
    // tinygltf reads the file; Glint names the extension.
    TestAsset a = plainAsset(cubeMesh());
    a.json["extensionsUsed"] = {"KHR_texture_basisu"};
    a.json["extensionsRequired"] = {"KHR_texture_basisu"};
    EXPECT_EQ(errorOf(a),
              "the file requires extension KHR_texture_basisu, which Glint does not support");
    // A compression Glint does not know leaves accessors without bufferViews, which tinygltf
    // rejects: the extension is named rather than tinygltf's complaint.
    TestAsset b = dracoAsset(cubeMesh());
    nlohmann::json& p = primitiveOf(b);
    p["extensions"]["EXT_future_compression"] = p["extensions"]["KHR_draco_mesh_compression"];
    p["extensions"].erase("KHR_draco_mesh_compression");
    b.json["extensionsUsed"] = {"EXT_future_compression"};
    b.json["extensionsRequired"] = {"EXT_future_compression"};
    EXPECT_EQ(errorOf(b),
              "the file requires extension EXT_future_compression, which Glint does not support");
}

TEST(GltfCompression, TheFuzzSeedsDecodeUnderTheHarnessLimits) {
    // The seeds made with draco_transcoder and gltfpack (fuzz/corpus/gltf, docs/robustness.md)
    // load as the harness loads them, so that fuzzing starts inside the decoders.
    int seeds = 0;
    for (const auto& e :
         std::filesystem::directory_iterator(std::string(GLINT_FUZZ_DIR) + "/corpus/gltf")) {
        const std::string name = e.path().filename().string();
        if (!name.starts_with("draco-") && !name.starts_with("meshopt-")) continue;
        SCOPED_TRACE(name);
        std::ifstream in(e.path(), std::ios::binary);
        const std::string bytes((std::istreambuf_iterator<char>(in)),
                                std::istreambuf_iterator<char>());
        GltfOptions options;
        options.limits.readFiles = false;
        options.limits.memoryBytes = size_t(64) << 20;
        std::vector<Diagnostic> warnings;
        EXPECT_GT(parseGltf(bytes, name, warnings, options).triangles(), 0u);
        ++seeds;
    }
    EXPECT_GE(seeds, 6);
}

TEST(GltfCompression, StbImageIsLibstbsNotLibdracos) {
    // Debian's libdraco exports its own stb_image (and tinygltf): the link order must leave
    // Glint's image reading to libstb (src/CMakeLists.txt).
    Dl_info info{};
    ASSERT_NE(dladdr(reinterpret_cast<void*>(&stbi_load_from_memory), &info), 0);
    ASSERT_NE(info.dli_fname, nullptr);
    EXPECT_THAT(info.dli_fname, HasSubstr("libstb.so"));
    ASSERT_NE(dladdr(reinterpret_cast<void*>(&stbi_failure_reason), &info), 0);
    EXPECT_THAT(info.dli_fname, HasSubstr("libstb.so"));
}

}  // namespace
}  // namespace glint
