// Models, whatever file they came from: placing one in a scene under a transform
// (placeModel), and making a whole scene of one (frameModelScene).

#include "glint/scene/model.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "glint/math/mat4.h"
#include "glint/scene/model_framing.h"
#include "unit/test_support.h"

namespace glint {
namespace {

using test::expectNear;
using ::testing::HasSubstr;
using ::testing::StartsWith;

/// A unit right triangle in z = 0, named "tri.obj".
MeshData triangle() {
    MeshData m;
    m.name = "tri.obj";
    m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    m.triangles.push_back({{MeshData::Corner{0}, MeshData::Corner{1}, MeshData::Corner{2}}});
    return m;
}

Transform translation(double x, double y, double z) {
    return *Transform::fromMatrix(Mat4::translate(x, y, z));
}

/// A model `name` of the triangle placed by each of `placements` (nodes 1, 2, ...).
Model triangles(const std::string& name, const std::vector<Transform>& placements) {
    Model model;
    model.name = name;
    model.meshes.push_back(triangle());
    for (const Transform& t : placements)
        model.placements.push_back({0, t, static_cast<uint32_t>(model.placements.size() + 1)});
    return model;
}

/// Expects what `model` becomes, placed by `worldFromModel`, to lie in [lo, hi] (within `eps`:
/// instances have padded bounds).
void expectPlacedBounds(const Model& model, const Transform& worldFromModel, const Vec3& lo,
                        const Vec3& hi, double eps) {
    SceneBuilder builder;
    placeModel(builder, model, worldFromModel, builder.materialId());
    Bounds3f b = builder.finish()->primitives.bounds();
    expectNear(Vec3(b.lo), lo, eps);
    expectNear(Vec3(b.hi), hi, eps);
}

TEST(Model, OneMeshIsPlacedOnceAsItIs) {
    Model model = singleMeshModel(triangle());
    EXPECT_EQ(model.name, "tri.obj");
    ASSERT_EQ(model.placements.size(), 1u);
    EXPECT_TRUE(model.placements[0].worldFromObject.isIdentity());
    EXPECT_EQ(model.triangles(), 1u);
    expectPlacedBounds(model, translation(5, 0, 0), {5, 0, 0}, {6, 1, 0}, 1e-6);
}

TEST(Model, PlacementsComposeWithTheScenesTransform) {
    Model model = triangles("two.gltf", {translation(0, 10, 0), translation(0, 20, 0)});
    EXPECT_EQ(model.triangles(), 2u);
    expectPlacedBounds(model, translation(5, 0, 0), {5, 10, 0}, {6, 21, 0}, 1e-4);
}

TEST(Model, ASingularCompositionNamesTheNode) {
    const Transform thin = *Transform::fromMatrix(Mat4::scale(1e-200, 1, 1));
    Model model = triangles("big.gltf", {translation(0, 1, 0), thin});
    SceneBuilder builder;
    try {
        placeModel(builder, model, thin, 0);
        FAIL() << "no SceneError";
    } catch (const SceneError& e) {
        EXPECT_EQ(e.diagnostic().loc.file, "big.gltf");
        EXPECT_EQ(e.diagnostic().message,
                  "node 2: its transform, with the scene's, is singular or too large");
    }
}

TEST(CameraChoice, NoneANumberOrAName) {
    using Kind = CameraChoice::Kind;
    EXPECT_EQ(CameraChoice::parse("").kind, Kind::First);
    EXPECT_EQ(CameraChoice::parse("none").kind, Kind::None);
    CameraChoice n = CameraChoice::parse("12");
    EXPECT_EQ(n.kind, Kind::Index);
    EXPECT_EQ(n.index, 12u);
    EXPECT_EQ(n.describe(), "camera 12");
    EXPECT_EQ(CameraChoice::parse("99999999999999999999999").index, SIZE_MAX);
    CameraChoice s = CameraChoice::parse("Side 2");
    EXPECT_EQ(s.kind, Kind::Name);
    EXPECT_EQ(s.name, "Side 2");
    EXPECT_EQ(s.describe(), "camera 'Side 2'");
    EXPECT_EQ(CameraChoice::parse("-1").kind, Kind::Name);  // not a number of a camera
}

TEST(ModelFraming, AModelWithoutCameraOrLightsGetsGlintsAndSaysSo) {
    ModelScene m = frameModelScene(singleMeshModel(triangle()));
    EXPECT_EQ(m.scene->width, 640);
    EXPECT_EQ(m.scene->height, 480);
    ASSERT_TRUE(m.scene->camera);
    EXPECT_EQ(m.scene->lights.size(), 2u);
    EXPECT_EQ(m.scene->primitives.planeCount(), 1u);  // the floor
    EXPECT_THAT(m.note, StartsWith("tri.obj has no camera or lights: framing it with a camera"));
}

TEST(ModelFraming, TheModelsOwnCameraAndLightsAreKept) {
    Model model = singleMeshModel(triangle());
    model.camera = ModelCamera{{{0, 0, 5}, {0, 0, 0}, {0, 1, 0}, 30}, 2.0, "camera 0 (node 1)"};
    Light light;
    light.position = {0, 0, 3};
    model.lights.push_back(light);
    ModelScene m = frameModelScene(model);
    EXPECT_EQ(m.note, "");  // nothing assumed
    EXPECT_EQ(m.scene->camera->fovyDegrees, 30);
    EXPECT_EQ(m.scene->height, 320);  // 640 wide at the camera's aspect ratio
    ASSERT_EQ(m.scene->lights.size(), 1u);
    EXPECT_EQ(m.scene->lights[0].position, Vec3(0, 0, 3));
    model.lights.clear();
    EXPECT_THAT(frameModelScene(model).note,
                HasSubstr("has no lights: lighting it with a key and a fill directional light "
                          "(and its camera 0 (node 1))"));
}

TEST(ModelFraming, AModelOfNothingVisibleIsAnError) {
    MeshData flat = triangle();
    flat.positions[2] = {2, 0, 0};  // zero area
    EXPECT_THROW(frameModelScene(singleMeshModel(flat)), SceneError);
}

}  // namespace
}  // namespace glint
