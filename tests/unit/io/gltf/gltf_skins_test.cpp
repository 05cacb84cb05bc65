// Skinned glTF meshes (io/gltf/gltf_skins.cpp): posed by their joints in the pose the nodes'
// transforms give, not by the transform of the node that places them, which glTF says to
// ignore. The assets are written here: a strip 1.85 long lying along the mesh's +z, as a
// Blender export's Z-up mesh lies, whose skeleton stands it upright in glTF's Y-up world.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "glint/io/gltf/gltf_loader.h"
#include "unit/io/gltf/gltf_asset_builder.h"
#include "unit/io/gltf/gltf_test_support.h"
#include "unit/test_support.h"

namespace glint {
namespace {

using namespace glint::test;
using ::testing::HasSubstr;

/// What to vary in the skinned strip.
struct StripOptions {
    std::vector<int> joints = {0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0,
                               0, 1, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0};
    /// Vertices 0-1 follow joint 0, 4-5 joint 1, and 2-3 (at the joint) both, with weights
    /// that sum to 0.5: they are normalised.
    std::vector<float> weights = {1,     0,     0, 0, 1, 0, 0, 0, 0.25f, 0.25f, 0, 0,
                                  0.25f, 0.25f, 0, 0, 1, 0, 0, 0, 1,     0,     0, 0};
    std::string upperRotation;  ///< The upper joint's rotation, e.g. ", \"rotation\": [...]".
    bool inverseBind = true;
    /// The inverse bind matrices, column by column: the identity, and a translation by -1
    /// along z (the upper joint's bind pose was 1 along z).
    std::vector<float> inverseBindMatrices = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0,  1,
                                              1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, -1, 1};
    std::string skinJoints = "[1, 2]";  ///< The skin's joints.
    std::string skin = "0";             ///< The mesh node's skin.
    std::string moreNodes;              ///< Further nodes (from 3), e.g. an unskinned placement.
    std::string sceneNodes;  ///< The scene's roots; empty: 0, 1 and 3 if there is a node 3.
};

/// The strip: vertices (+-0.2, 0, z) for z = 0, 1 and 1.85, normals -y, placed by node 0 with
/// a wild transform (translated by 5, turned 90 degrees about x, scaled by 0.01) and skin 0
/// 'Armature' of joints 1 'root' (at (2, 0, 0), turned -90 degrees about x: the mesh's +z
/// becomes +y, and its -y +z) and its child 2 'upper' (1 along root's z: the joint at the
/// strip's middle).
std::string strip(const StripOptions& o = {}) {
    GltfAsset a;
    int position = a.floats(
        {-0.2f, 0, 0, 0.2f, 0, 0, -0.2f, 0, 1, 0.2f, 0, 1, -0.2f, 0, 1.85f, 0.2f, 0, 1.85f},
        "VEC3");
    int normal = a.floats({0, -1, 0, 0, -1, 0, 0, -1, 0, 0, -1, 0, 0, -1, 0, 0, -1, 0}, "VEC3");
    int joints = a.integers(o.joints, GltfAsset::kUbyte, "VEC4");
    int weights = a.floats(o.weights, "VEC4");
    int indices = a.integers({0, 1, 3, 0, 3, 2, 2, 3, 5, 2, 5, 4}, GltfAsset::kUbyte, "SCALAR");
    int ibm = a.floats(o.inverseBindMatrices, "MAT4");
    const std::string scene = !o.sceneNodes.empty() ? o.sceneNodes
                              : o.moreNodes.empty() ? "[0, 1]"
                                                    : "[0, 1, 3]";
    return a.text(R"("meshes": [{"name": "strip", "primitives": [{"attributes": {"POSITION": )" +
                  std::to_string(position) + R"(, "NORMAL": )" + std::to_string(normal) +
                  R"(, "JOINTS_0": )" + std::to_string(joints) + R"(, "WEIGHTS_0": )" +
                  std::to_string(weights) + R"(}, "indices": )" + std::to_string(indices) + R"(}]}],
        "skins": [{"name": "Armature", "joints": )" +
                  o.skinJoints +
                  (o.inverseBind ? R"(, "inverseBindMatrices": )" + std::to_string(ibm) : "") +
                  R"(}],
        "nodes": [{"mesh": 0, "skin": )" +
                  o.skin + R"(, "translation": [5, 5, 5],
                   "rotation": [0.70710678, 0, 0, 0.70710678], "scale": [0.01, 0.01, 0.01]},
                  {"name": "root", "translation": [2, 0, 0],
                   "rotation": [-0.70710678, 0, 0, 0.70710678], "children": [2]},
                  {"name": "upper", "translation": [0, 0, 1])" +
                  o.upperRotation + "}" + o.moreNodes + R"(],
        "scenes": [{"nodes": )" +
                  scene + R"(}])");
}

/// The world position of vertex `i` of the mesh placement `p` places.
Vec3 placed(const Model& model, size_t p, size_t i) {
    const ModelPlacement& placement = model.placements[p];
    return placement.worldFromObject.point(Vec3(model.meshes[placement.mesh].positions[i]));
}

TEST(GltfSkins, ASkinnedMeshStandsAsItsJointsPlaceItNotAsItsNode) {
    Model model = parse(strip());
    ASSERT_EQ(model.placements.size(), 1u);
    EXPECT_TRUE(model.placements[0].worldFromObject.isIdentity());
    const MeshData& m = model.meshes[model.placements[0].mesh];
    // Hand-computed: (x, y, z) becomes (x + 2, z, -y): upright, 1.85 tall, from y = 0.
    Vec3 lo(1e9), hi(-1e9);
    for (size_t i = 0; i < m.positions.size(); ++i) {
        Vec3 p = placed(model, 0, i);
        lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
        hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
    }
    expectNear(lo, {1.8, 0, 0}, 1e-6);
    expectNear(hi, {2.2, 1.85, 0}, 1e-6);
    // Normals turn with it: -y becomes +z.
    for (const Vec3f& n : m.normals) expectNear(Vec3(n), {0, 0, 1}, 1e-6);
}

TEST(GltfSkins, VerticesBlendTheirJointsMatricesByTheirWeights) {
    // The upper joint turned 90 degrees about its y: the strip's top half bends towards +x.
    StripOptions o;
    o.upperRotation = R"(, "rotation": [0, 0.70710678, 0, 0.70710678])";
    Model model = parse(strip(o));
    // Vertex 4 (-0.2, 0, 1.85): 0.85 above the joint -> turned to (0.85, 0, 0.2) from it ->
    // (0.85, 0, 1.2) in root's space -> (2.85, 1.2, 0).
    expectNear(placed(model, 0, 4), {2.85, 1.2, 0}, 1e-6);
    expectNear(placed(model, 0, 5), {2.85, 0.8, 0}, 1e-6);
    expectNear(placed(model, 0, 0), {1.8, 0, 0}, 1e-6);  // joint 0 alone: not bent
    // Vertex 2 (-0.2, 0, 1), half and half (weights 0.25 and 0.25, normalised): joint 0 puts it
    // at (1.8, 1, 0), joint 1 at (2, 1.2, 0).
    expectNear(placed(model, 0, 2), {1.9, 1.1, 0}, 1e-6);
    expectNear(placed(model, 0, 3), {2.1, 0.9, 0}, 1e-6);
    for (const Vec3f& n : model.meshes[model.placements[0].mesh].normals)
        expectNear(Vec3(n), {0, 0, 1}, 1e-6);
}

TEST(GltfSkins, WithoutInverseBindMatricesTheyAreTheIdentity) {
    StripOptions o;
    o.inverseBind = false;
    // All on joint 0 (root), weights as normalised unsigned bytes would give them too.
    o.joints = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
    o.weights = {1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0};
    Model model = parse(strip(o));
    expectNear(placed(model, 0, 4), {1.8, 1.85, 0}, 1e-6);
}

TEST(GltfSkins, AMeshAlsoPlacedWithoutTheSkinIsPosedInACopy) {
    StripOptions o;
    o.moreNodes = R"(, {"mesh": 0, "translation": [0, 0, -3]})";
    Model model = parse(strip(o));
    ASSERT_EQ(model.placements.size(), 2u);
    EXPECT_NE(model.placements[0].mesh, model.placements[1].mesh);
    EXPECT_EQ(model.meshes.size(), 2u);
    expectNear(placed(model, 0, 4), {1.8, 1.85, 0}, 1e-6);    // posed
    expectNear(placed(model, 1, 4), {-0.2, 0, -1.15}, 1e-6);  // as the file has it, moved
}

TEST(GltfSkins, VerticesWithoutWeightsArePlacedByTheirNodeWithAWarning) {
    StripOptions o;
    o.weights = {0,    0,    0, 0, 1, 0, 0, 0, 0.5f, 0.5f, 0, 0,
                 0.5f, 0.5f, 0, 0, 1, 0, 0, 0, 1,    0,    0, 0};
    std::vector<Diagnostic> warnings;
    Model model = parse(strip(o), &warnings);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_EQ(warnings[0].message,
              "mesh 0 'strip': 1 of its 6 vertices have no joint weights (no JOINTS_0 and "
              "WEIGHTS_0, or weights of 0): they are placed by their node's transform");
    // Node 0: scaled by 0.01, turned about x (x stays), moved by 5.
    expectNear(placed(model, 0, 0), {4.998, 5, 5}, 1e-6);
}

TEST(GltfSkins, ErrorsNameTheSkin) {
    StripOptions o;
    o.joints = {0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 7, 0, 0, 0, 1, 0, 0, 0};
    EXPECT_EQ(errorParsing(strip(o)).message,
              "skin 0 'Armature': vertex 4 of mesh 0 'strip' uses joint 7, but the skin has 2 "
              "joints");
    StripOptions s;
    s.skin = "3";
    EXPECT_EQ(errorParsing(strip(s)).message,
              "skin 3 does not exist (the file has 1 skin): node 0 refers to it");
    StripOptions m;
    m.inverseBindMatrices.resize(16);
    EXPECT_EQ(errorParsing(strip(m)).message,
              "accessor 5 (inverseBindMatrices of skin 0 'Armature'): it has 1 matrix, fewer "
              "than the 2 its joints need");
    StripOptions j;
    j.skinJoints = "[1, 9]";
    EXPECT_EQ(errorParsing(strip(j)).message,
              "node 9 does not exist (the file has 3 nodes): joint 1 of skin 0 'Armature' refers "
              "to it");
    // A joint outside the scene whose ancestors go round in a circle.
    StripOptions c;
    c.skinJoints = "[3, 2]";
    c.moreNodes = R"(, {"name": "loop", "children": [4]}, {"children": [3]})";
    c.sceneNodes = "[0, 1]";
    EXPECT_THAT(errorParsing(strip(c)).message,
                HasSubstr("is its own ancestor: glTF nodes form trees (joint 0 of skin 0 "
                          "'Armature')"));
    StripOptions w;
    w.weights = {1, 0, 0, 0, -1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0};
    EXPECT_THAT(errorParsing(strip(w)).message,
                HasSubstr("(WEIGHTS_0 of mesh 0 'strip', primitive 0): element 1 has a weight "
                          "that is negative or not finite"));
}

TEST(GltfSkins, ABlenderExportedRigStandsAsBlendersImporterPosesIt) {
    // tests/data/gltf/make_blender_rig.py: a figure 1.85 m tall, its chest bent 40 degrees, its
    // mesh node under an armature node scaled 0.01. The reference bounds are those Blender's
    // own glTF importer gives the file.
    Model model = load("blender-rig.glb");
    ASSERT_EQ(model.placements.size(), 1u);
    const MeshData& m = model.meshes[model.placements[0].mesh];
    Vec3 lo(1e9), hi(-1e9);
    for (size_t i = 0; i < m.positions.size(); ++i) {
        Vec3 p = placed(model, 0, i);
        lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
        hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
    }
    expectNear(lo, {-0.2, 0, -0.12569}, 1e-4);
    expectNear(hi, {0.2, 1.73149, 0.64212}, 1e-4);
}

TEST(GltfSkins, ThePosedMeshIsPlacedInTheScene) {
    Model model = parse(strip());
    SceneBuilder builder;
    placeModel(builder, model, Transform(), builder.addMaterial(Material{}));
    auto scene = builder.finish();
    Bounds3f b = scene->primitives.bounds();
    EXPECT_NEAR(b.hi.y - b.lo.y, 1.85, 1e-5);  // upright, 1.85 tall: not 1.85 cm
    EXPECT_NEAR(b.lo.x, 1.8, 1e-5);
}

}  // namespace
}  // namespace glint
