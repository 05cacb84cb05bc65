// The scene builder: the graphics state every loader drives (transform stack, current material,
// attenuation, lens) and what it adds under that state.

#include "glint/scene/scene_builder.h"

#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "glint/math/mat4.h"
#include "unit/test_support.h"

namespace glint {
namespace {

using test::expectNear;

/// A unit right triangle in z = 0, in world space.
const Vec3 kTriangle[3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};

TEST(SceneBuilder, TransformsRightMultiplyAndPopRestoresThePushedOne) {
    SceneBuilder b;
    expectNear(b.transform().point({1, 2, 3}), {1, 2, 3});
    b.applyTransform(Mat4::translate(10, 0, 0));
    b.pushTransform();
    b.applyTransform(Mat4::scale(2, 2, 2));  // acts first: scaled, then translated
    expectNear(b.transform().point({1, 0, 0}), {12, 0, 0});
    EXPECT_TRUE(b.popTransform());
    expectNear(b.transform().point({1, 0, 0}), {11, 0, 0});
}

TEST(SceneBuilder, PopWithNothingPushedChangesNothing) {
    SceneBuilder b;
    b.applyTransform(Mat4::translate(0, 5, 0));
    EXPECT_FALSE(b.popTransform());
    expectNear(b.transform().point({0, 0, 0}), {0, 5, 0});
}

TEST(SceneBuilder, ASingularTransformIsABuildErrorWhenUsed) {
    SceneBuilder b;
    b.pushTransform();
    b.applyTransform(Mat4::scale(1, 0, 1));  // applying it is fine; using it is not
    EXPECT_THROW(b.transform(), BuildError);
    EXPECT_THROW(b.addSphere({0, 0, 0}, 1), BuildError);
    EXPECT_TRUE(b.popTransform());
    EXPECT_NO_THROW(b.transform());
}

TEST(SceneBuilder, TheCurrentMaterialIsAddedOnceUntilItChanges) {
    SceneBuilder b;
    uint32_t first = b.materialId();
    EXPECT_EQ(b.materialId(), first);
    EXPECT_EQ(b.scene().materials.size(), 1u);
    b.editMaterial().diffuse = Vec3(1, 0, 0);
    uint32_t red = b.materialId();
    EXPECT_NE(red, first);
    EXPECT_EQ(b.scene().materials[red].diffuse, Vec3(1, 0, 0));
    // Changed to an equal value: Scene::addMaterial reuses the last material.
    b.editMaterial().diffuse = Vec3(1, 0, 0);
    EXPECT_EQ(b.materialId(), red);
    EXPECT_EQ(b.scene().materials.size(), 2u);
    b.setMaterial(Material{});  // the whole material: the first one again, added anew
    EXPECT_EQ(b.scene().materials[b.materialId()], Material{});
    EXPECT_EQ(b.scene().materials.size(), 3u);
}

TEST(SceneBuilder, AnotherMaterialMakesTheCurrentOneBeAddedAgain) {
    SceneBuilder b;
    uint32_t current = b.materialId();
    Material glow;
    glow.emission = Vec3(1);
    uint32_t other = b.addMaterial(glow);
    EXPECT_NE(other, current);
    uint32_t again = b.materialId();
    EXPECT_NE(again, other);
    EXPECT_EQ(b.scene().materials[again], b.material());
}

TEST(SceneBuilder, PointLightsTakeTheAttenuationCurrentWhenAdded) {
    SceneBuilder b;
    b.addPointLight({0, 1, 0}, Vec3(1));
    b.setAttenuation({0, 0, 1});
    b.addPointLight({0, 2, 0}, Vec3(1));
    const auto& lights = b.scene().lights;
    ASSERT_EQ(lights.size(), 2u);
    EXPECT_EQ(lights[0].attenuation, Vec3(1, 0, 0));
    EXPECT_EQ(lights[1].attenuation, Vec3(0, 0, 1));
    EXPECT_EQ(lights[1].position, Vec3(0, 2, 0));
}

TEST(SceneBuilder, AQuadLightAddsItsEmittingSurface) {
    SceneBuilder b;
    LightSpec quad;
    quad.kind = LightSpec::Kind::Quad;
    quad.edge1 = {1, 0, 0};
    quad.edge2 = {0, 1, 0};
    quad.color = Vec3(5);
    b.addQuadLight(quad);
    std::unique_ptr<Scene> scene = b.finish();
    EXPECT_EQ(scene->lights.size(), 1u);
    ASSERT_EQ(scene->primitives.triangleCount(), 2u);
    const Material& m = scene->materials[scene->primitives.materialOf(0)];
    EXPECT_EQ(m.emission, Vec3(5));
    EXPECT_TRUE(m.frontEmissionOnly);
}

TEST(SceneBuilder, GeometryTakesTheCurrentMaterial) {
    SceneBuilder b;
    b.editMaterial().diffuse = Vec3(0, 1, 0);
    EXPECT_TRUE(b.addTriangle(kTriangle, nullptr));
    const Vec3 flat[3] = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
    EXPECT_FALSE(b.addTriangle(flat, nullptr));  // zero area: skipped
    EXPECT_TRUE(b.addSphere({0, 0, 5}, 1));
    EXPECT_FALSE(b.addSphere({0, 0, 5}, 0));  // radius 0: skipped
    std::unique_ptr<Scene> scene = b.finish();
    ASSERT_EQ(scene->primitives.size(), 2u);
    for (uint32_t id = 0; id < 2; ++id)
        EXPECT_EQ(scene->materials[scene->primitives.materialOf(id)].diffuse, Vec3(0, 1, 0));
}

TEST(SceneBuilder, ShapesBeyondTheCoordinateRangeAreBuildErrors) {
    SceneBuilder b;
    b.applyTransform(Mat4::scale(1e17, 1e17, 1e17));
    try {
        b.addShape(ShapeKind::Box, Mat4::scale(100, 100, 100), 1);
        FAIL() << "no BuildError";
    } catch (const BuildError& e) {
        EXPECT_STREQ(e.what(), "the box reaches beyond the supported coordinate range (1e18)");
    }
    EXPECT_THROW(b.addSphere({0, 0, 0}, 100), BuildError);
}

TEST(SceneBuilder, MeshesArePlacedWhenFinishedAndTheLensReachesTheCamera) {
    MeshData mesh;
    mesh.name = "tri";
    mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    mesh.triangles.push_back({{MeshData::Corner{0}, MeshData::Corner{1}, MeshData::Corner{2}}});
    SceneBuilder b;
    b.setLens(0.5, 3);  // before the camera, as a scene file may give it
    b.scene().camera = CameraSpec{{0, 0, 5}, {0, 0, 0}, {0, 1, 0}, 45};
    b.placeMesh(mesh, Transform(), b.materialId());
    b.placeMesh(mesh, *Transform::fromMatrix(Mat4::translate(3, 0, 0)), b.materialId());
    EXPECT_EQ(b.scene().primitives.size(), 0u);  // not yet
    std::unique_ptr<Scene> scene = b.finish();
    EXPECT_EQ(scene->primitives.instanceCount(), 2u);  // placed twice: stored once
    EXPECT_EQ(scene->camera->apertureRadius, 0.5);
    EXPECT_EQ(scene->camera->focusDistance, 3);
}

}  // namespace
}  // namespace glint
