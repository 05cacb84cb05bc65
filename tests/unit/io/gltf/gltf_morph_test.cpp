// glTF morph targets (io/gltf/gltf_meshes.cpp; the glTF specification, 3.7.2.2): positions,
// normals and tangents moved by their targets' weighted displacements, with the mesh's own
// weights or those readMesh is given, and the checks of targets and weights. Assets are written
// by the tests, but for the Khronos sample AnimatedMorphCube.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

#include "glint/io/gltf/gltf_internal.h"
#include "glint/io/gltf/gltf_loader.h"
#include "unit/io/gltf/gltf_asset_builder.h"
#include "unit/io/gltf/gltf_test_support.h"
#include "unit/test_support.h"

namespace glint {
namespace {

using namespace glint::test;
using ::testing::HasSubstr;
using ::testing::Not;

/// Mesh 0 'Square': the unit square in z = 0 facing +z ((0,0,0) (1,0,0) (1,1,0) (0,1,0)),
/// indexed as two triangles, with normals; its primitive has the morph targets `targets` (JSON
/// objects) and the mesh has `weights` (a JSON array) when given.
struct Square {
    GltfAsset asset;
    int position, normal, indices;

    Square() {
        position = asset.floats({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0}, "VEC3");
        normal = asset.floats({0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3");
        indices = asset.integers({0, 1, 2, 0, 2, 3}, GltfAsset::kUshort, "SCALAR");
    }
    std::string text(const std::vector<std::string>& targets, const std::string& weights = "",
                     const std::string& attributes = "") const {
        std::string list;
        for (const std::string& t : targets) list += (list.empty() ? "" : ", ") + t;
        return asset.text(R"("meshes": [{"name": "Square", "primitives": [{"attributes": )"
                          R"({"POSITION": )" +
                          std::to_string(position) + R"(, "NORMAL": )" + std::to_string(normal) +
                          attributes + R"(}, "indices": )" + std::to_string(indices) +
                          R"(, "targets": [)" + list + "]}]" +
                          (weights.empty() ? "" : R"(, "weights": )" + weights) +
                          R"(}], "nodes": [{"mesh": 0}])");
    }
};

/// A morph target that moves `attribute` by accessor `accessor`.
std::string target(const char* attribute, int accessor) {
    return std::string("{\"") + attribute + "\": " + std::to_string(accessor) + "}";
}

/// Mesh 0 of `text` as readMesh reads it with `morphWeights`.
MeshData readWith(const std::string& text, const std::vector<double>& morphWeights) {
    std::vector<Diagnostic> warnings;
    GltfOptions options;
    const std::string file = "t.gltf";
    gltf::Context ctx(file, warnings, options);
    gltf::parseContainer(ctx, text);
    gltf::Materials materials(ctx);
    return gltf::readMesh(ctx, 0, gltf::countMesh(ctx, 0), materials, nullptr, &morphWeights);
}

/// The error readWith() gives.
Diagnostic errorReading(const std::string& text, const std::vector<double>& morphWeights) {
    try {
        readWith(text, morphWeights);
    } catch (const SceneError& e) {
        return e.diagnostic();
    }
    ADD_FAILURE() << "no SceneError for:\n" << text;
    return {};
}

void expectPositions(const MeshData& m, const std::vector<Vec3f>& expected) {
    ASSERT_EQ(m.positions.size(), expected.size());
    for (size_t i = 0; i < expected.size(); ++i) EXPECT_EQ(m.positions[i], expected[i]) << i;
}

TEST(GltfMorph, ATargetWeightOfHalfMovesPositionsHalfway) {
    Square s;
    int moves = s.asset.floats({0, 0, 2, 0, 0, 4, 2, 2, 2, -1, 0, 1}, "VEC3");
    Model model = parse(s.text({target("POSITION", moves)}, "[0.5]"));
    expectPositions(model.meshes[0], {{0, 0, 1}, {1, 0, 2}, {2, 2, 1}, {-0.5f, 1, 0.5f}});
}

TEST(GltfMorph, TwoTargetsAdd) {
    Square s;
    int up = s.asset.floats({0, 0, 2, 0, 0, 2, 0, 0, 2, 0, 0, 2}, "VEC3");
    int right = s.asset.floats({4, 0, 0, 4, 0, 0, 4, 0, 0, 4, 0, 0}, "VEC3");
    Model model = parse(s.text({target("POSITION", up), target("POSITION", right)}, "[0.5, 0.25]"));
    expectPositions(model.meshes[0], {{1, 0, 1}, {2, 0, 1}, {2, 1, 1}, {1, 1, 1}});
}

TEST(GltfMorph, WithoutWeightsTheBaseShapeIsKept) {
    Square s;
    int moves = s.asset.floats({0, 0, 2, 0, 0, 2, 0, 0, 2, 0, 0, 2}, "VEC3");
    Model model = parse(s.text({target("POSITION", moves)}));  // no mesh weights: zeros
    expectPositions(model.meshes[0], {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
}

TEST(GltfMorph, NormalsAndTangentsAreDisplacedThenRenormalised) {
    Square s;
    int tangents = s.asset.floats({1, 0, 0, -1, 1, 0, 0, -1, 1, 0, 0, -1, 1, 0, 0, -1}, "VEC4");
    int normalMoves = s.asset.floats({2, 0, 0, 2, 0, 0, 2, 0, 0, 2, 0, 0}, "VEC3");
    int tangentMoves = s.asset.floats({0, 2, 0, 0, 2, 0, 0, 2, 0, 0, 2, 0}, "VEC3");
    Model model = parse(s.text({R"({"NORMAL": )" + std::to_string(normalMoves) +
                                R"(, "TANGENT": )" + std::to_string(tangentMoves) + "}"},
                               "[0.5]", R"(, "TANGENT": )" + std::to_string(tangents)));
    const MeshData& m = model.meshes[0];
    ASSERT_EQ(m.normals.size(), 4u);
    ASSERT_EQ(m.tangents.size(), 4u);
    const double r = std::sqrt(0.5);
    for (size_t i = 0; i < 4; ++i) {
        expectNear(Vec3(m.normals[i]), {r, 0, r}, 1e-7);  // (0,0,1) + (1,0,0), normalised
        const auto& t = m.tangents[i];
        expectNear({t[0], t[1], t[2]}, {r, r, 0}, 1e-7);  // (1,0,0) + (0,1,0), normalised
        EXPECT_EQ(t[3], -1);                              // w is not morphed
    }
    expectPositions(m, {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});  // no POSITION target
}

TEST(GltfMorph, ASparseTargetMovesOnlyTheVerticesItNames) {
    // Over zeros (no bufferView), as exporters write most targets: vertex 2 alone moves.
    Square s;
    int moves = s.asset.sparseFloats(4, "VEC3", {2}, {0, 0, 2});
    Model model = parse(s.text({target("POSITION", moves)}, "[0.5]"));
    expectPositions(model.meshes[0], {{0, 0, 0}, {1, 0, 0}, {1, 1, 1}, {0, 1, 0}});

    // Over a bufferView: vertex 0's value is replaced, not added to.
    Square d;
    int over =
        d.asset.sparseFloats(4, "VEC3", {0}, {0, 0, 0}, {2, 0, 0, 2, 0, 0, 2, 0, 0, 2, 0, 0});
    model = parse(d.text({target("POSITION", over)}, "[0.5]"));
    expectPositions(model.meshes[0], {{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}});
}

TEST(GltfMorph, TheMeshsOwnWeightsApplyWhenNoneAreGiven) {
    Square s;
    int moves = s.asset.floats({0, 0, 2, 0, 0, 2, 0, 0, 2, 0, 0, 2}, "VEC3");
    const std::string text = s.text({target("POSITION", moves)}, "[0.5]");
    expectPositions(parse(text).meshes[0], {{0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}});
    // Weights given (a node's, or an animation's at a time) replace the mesh's own.
    expectPositions(readWith(text, {1.5}), {{0, 0, 3}, {1, 0, 3}, {1, 1, 3}, {0, 1, 3}});
    expectPositions(readWith(text, {0}), {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
}

TEST(GltfMorph, EveryPrimitiveMustHaveAsManyTargets) {
    Square s;
    int moves = s.asset.floats({0, 0, 2, 0, 0, 2, 0, 0, 2, 0, 0, 2}, "VEC3");
    const std::string primitive = R"({"attributes": {"POSITION": )" + std::to_string(s.position) +
                                  R"(}, "indices": )" + std::to_string(s.indices);
    const std::string text = s.asset.text(
        R"("meshes": [{"name": "Square", "primitives": [)" + primitive + R"(, "targets": [)" +
        target("POSITION", moves) + "]}, " + primitive + R"(}]}], "nodes": [{"mesh": 0}])");
    EXPECT_EQ(errorParsing(text).message,
              "mesh 0 'Square', primitive 1: it has 0 morph targets, but primitive 0 has 1 "
              "(every primitive of a mesh must have as many)");
}

TEST(GltfMorph, TargetAccessorsAreCheckedAsTheBaseOnes) {
    Square c;
    int three = c.asset.floats({0, 0, 2, 0, 0, 2, 0, 0, 2}, "VEC3");
    EXPECT_EQ(errorParsing(c.text({target("POSITION", three)}, "[0.5]")).message,
              "accessor 3 (POSITION of morph target 0 of mesh 0 'Square', primitive 0): it has 3 "
              "elements, but POSITION has 4");
    Square t;
    int vec2 = t.asset.floats({0, 2, 0, 2, 0, 2, 0, 2}, "VEC2");
    EXPECT_EQ(errorParsing(t.text({target("NORMAL", vec2)})).message,
              "accessor 3 (NORMAL of morph target 0 of mesh 0 'Square', primitive 0): its "
              "elements are VEC2, not VEC3");
    Square b;
    int bytes = b.asset.integers({0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1}, GltfAsset::kUbyte, "VEC3");
    EXPECT_EQ(errorParsing(b.text({target("POSITION", bytes)})).message,
              "accessor 3 (POSITION of morph target 0 of mesh 0 'Square', primitive 0): its "
              "components must be floats, or normalised bytes or shorts");
    Square n;
    const float inf = std::numeric_limits<float>::infinity();
    int infinite = n.asset.floats({0, 0, 2, 0, inf, 2, 0, 0, 2, 0, 0, 2}, "VEC3");
    EXPECT_EQ(errorParsing(n.text({target("POSITION", infinite)}, "[0.5]")).message,
              "accessor 3 (POSITION of morph target 0 of mesh 0 'Square', primitive 0): element "
              "1 is not a finite displacement");
}

TEST(GltfMorph, NormalisedShortTargetsAreRead) {
    Square s;
    int shorts = s.asset.integers({0, 0, 32767, 0, 0, -32767, 0, 0, 0, 0, 0, 0}, GltfAsset::kShort,
                                  "VEC3", true);
    Model model = parse(s.text({target("POSITION", shorts)}, "[0.5]"));
    expectPositions(model.meshes[0], {{0, 0, 0.5f}, {1, 0, -0.5f}, {1, 1, 0}, {0, 1, 0}});
}

TEST(GltfMorph, WeightsMustBeOnePerTargetAndFinite) {
    Square s;
    int moves = s.asset.floats({0, 0, 2, 0, 0, 2, 0, 0, 2, 0, 0, 2}, "VEC3");
    EXPECT_EQ(errorParsing(s.text({target("POSITION", moves)}, "[0.5, 1]")).message,
              "mesh 0 'Square': it has 2 weights, but 1 morph target (one weight per target)");
    const std::string text = s.text({target("POSITION", moves)});
    // JSON has no NaN (and tinygltf refuses 1e999): a non-finite weight of the mesh is put in
    // after parsing.
    std::vector<Diagnostic> warnings;
    GltfOptions options;
    const std::string file = "t.gltf";
    gltf::Context ctx(file, warnings, options);
    gltf::parseContainer(ctx, text);
    ctx.model.meshes[0].weights = {std::numeric_limits<double>::quiet_NaN()};
    try {
        gltf::morphTargetCount(ctx, 0);
        ADD_FAILURE() << "no SceneError for a NaN weight";
    } catch (const SceneError& e) {
        EXPECT_EQ(e.diagnostic().message, "mesh 0 'Square': weight 0 is not a finite number");
    }
    EXPECT_EQ(errorReading(text, {0.5, 1}).message,
              "mesh 0 'Square': 2 morph target weights are given for its 1 morph target");
    EXPECT_EQ(errorReading(text, {std::numeric_limits<double>::quiet_NaN()}).message,
              "mesh 0 'Square': morph target weight 0 is not a finite number");
    EXPECT_EQ(errorReading(text, {std::numeric_limits<double>::infinity()}).message,
              "mesh 0 'Square': morph target weight 0 is not a finite number");
}

TEST(GltfMorph, OtherTargetAttributesAreIgnoredWithAWarning) {
    Square s;
    int uvs = s.asset.floats({0, 1, 0, 1, 0, 1, 0, 1}, "VEC2");
    std::vector<Diagnostic> warnings;
    Model model =
        parse(s.text({target("TEXCOORD_0", uvs), target("TEXCOORD_0", uvs)}, "[1, 1]"), &warnings);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_EQ(warnings[0].message,
              "mesh 0 'Square', primitive 0: morph target attribute TEXCOORD_0 is ignored: only "
              "POSITION, NORMAL and TANGENT are morphed (reported once)");
    expectPositions(model.meshes[0], {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
}

/// The Khronos sample AnimatedMorphCube (two targets, "thin" and "angle", moving the bottom of a
/// cube of side 0.02 up), where the machine has it.
const std::string kMorphCube = "/work/shared/real-world/gltf-ext/AnimatedMorphCube";

TEST(GltfMorph, TheKhronosAnimatedMorphCubeLoadsWithoutAMorphWarning) {
    const std::string gltf = kMorphCube + "/glTF/AnimatedMorphCube.gltf";
    if (!std::filesystem::exists(gltf)) GTEST_SKIP() << gltf << " is not on this machine";
    std::vector<Diagnostic> warnings;
    Model model = loadGltf(gltf, warnings);
    for (const Diagnostic& w : warnings) EXPECT_THAT(w.message, Not(HasSubstr("morph")));
    ASSERT_EQ(model.meshes.size(), 1u);
    ASSERT_EQ(model.meshes[0].positions.size(), 24u);

    // Its "thin" target at weight 1 lifts the bottom (y = -0.01) by 0.0189.
    std::ifstream in(kMorphCube + "/glTF-Binary/AnimatedMorphCube.glb", std::ios::binary);
    const std::string glb((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    ASSERT_FALSE(glb.empty());
    std::vector<Diagnostic> readWarnings;
    GltfOptions options;
    const std::string file = "AnimatedMorphCube.glb";
    gltf::Context ctx(file, readWarnings, options);
    gltf::parseContainer(ctx, glb);
    ASSERT_EQ(gltf::morphTargetCount(ctx, 0), 2u);
    gltf::Materials materials(ctx);
    const std::vector<double> thin = {1, 0};
    MeshData m = gltf::readMesh(ctx, 0, gltf::countMesh(ctx, 0), materials, nullptr, &thin);
    float low = 1, high = -1;
    for (const Vec3f& p : m.positions) {
        low = std::min(low, p.y);
        high = std::max(high, p.y);
    }
    EXPECT_NEAR(low, -0.01 + 0.01893253, 1e-6);
    EXPECT_NEAR(high, 0.01, 1e-6);
    for (const Vec3f& n : m.normals) EXPECT_NEAR(length(Vec3(n)), 1, 1e-6);
}

}  // namespace
}  // namespace glint
