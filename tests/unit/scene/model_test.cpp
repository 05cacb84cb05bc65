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

/// The world-space bounds of what `model` becomes placed by `worldFromModel`.
Bounds3f placedBounds(const Model& model, const Transform& worldFromModel) {
    SceneBuilder builder;
    placeModel(builder, model, worldFromModel, builder.materialId());
    return builder.finish()->primitives.bounds();
}

TEST(Model, OneMeshIsPlacedOnceAsItIs) {
    Model model = singleMeshModel(triangle());
    EXPECT_EQ(model.name, "tri.obj");
    ASSERT_EQ(model.placements.size(), 1u);
    EXPECT_TRUE(model.placements[0].worldFromObject.isIdentity());
    EXPECT_EQ(model.triangles(), 1u);
    Bounds3f b = placedBounds(model, translation(5, 0, 0));
    expectNear(Vec3(b.lo), {5, 0, 0}, 1e-6);
    expectNear(Vec3(b.hi), {6, 1, 0}, 1e-6);
}

TEST(Model, PlacementsComposeWithTheScenesTransform) {
    Model model;
    model.name = "two.gltf";
    model.meshes.push_back(triangle());
    model.placements.push_back({0, translation(0, 10, 0), 3});
    model.placements.push_back({0, translation(0, 20, 0), 4});
    EXPECT_EQ(model.triangles(), 2u);
    Bounds3f b = placedBounds(model, translation(5, 0, 0));  // instances: padded bounds
    expectNear(Vec3(b.lo), {5, 10, 0}, 1e-4);
    expectNear(Vec3(b.hi), {6, 21, 0}, 1e-4);
}

TEST(Model, ASingularCompositionNamesTheNode) {
    Model model;
    model.name = "big.gltf";
    model.meshes.push_back(triangle());
    model.placements.push_back({0, *Transform::fromMatrix(Mat4::scale(1e-200, 1, 1)), 7});
    SceneBuilder builder;
    try {
        placeModel(builder, model, *Transform::fromMatrix(Mat4::scale(1e-200, 1, 1)), 0);
        FAIL() << "no SceneError";
    } catch (const SceneError& e) {
        EXPECT_EQ(e.diagnostic().loc.file, "big.gltf");
        EXPECT_EQ(e.diagnostic().message,
                  "node 7: its transform, with the scene's, is singular or too large");
    }
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
