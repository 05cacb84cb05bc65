// The scene commands for meshes and textures: `mesh`, `texture`, `checker`. Mesh files are in
// tests/data/meshes; scenes are parsed as if they were a file in that directory, so that the
// names they use resolve there.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <numbers>

#include "glint/io/course/course_loader.h"
#include "glint/render/integrators/whitted.h"
#include "unit/io/course/course_test_support.h"
#include "unit/test_support.h"

namespace glint {
namespace {

using test::expectError;
using test::expectNear;
using test::kCamera;
using test::shoot;
using ::testing::HasSubstr;

const std::string kDir = std::string(GLINT_TEST_DATA_DIR) + "/meshes/";
const std::string kSceneFile = kDir + "scene.test";

std::unique_ptr<Scene> parseIn(const std::string& body, std::vector<Diagnostic>* warnings = nullptr,
                               const LoadLimits& limits = {}) {
    std::vector<Diagnostic> w;
    auto scene = parseCourseScene(body + kCamera, kSceneFile, w, CourseOptions{limits});
    if (warnings)
        *warnings = w;
    else
        EXPECT_TRUE(w.empty()) << w.front().format("warning");
    return scene;
}

Diagnostic errorIn(const std::string& body, const LoadLimits& limits = {}) {
    std::vector<Diagnostic> w;
    try {
        parseCourseScene(body + kCamera, kSceneFile, w, CourseOptions{limits});
    } catch (const SceneError& e) {
        return e.diagnostic();
    }
    ADD_FAILURE() << "no error for:\n" << body;
    return {};
}

std::optional<SurfaceInteraction> down(Scene& s, double x, double y, double z = 10) {
    return shoot(s, {x, y, z}, {0, 0, -1});
}

TEST(CourseMeshes, MeshIsPlacedByTheCurrentTransformWithTheCurrentMaterial) {
    auto s = parseIn(
        "diffuse 0.1 0.2 0.3\npushTransform\ntranslate 5 0 1\nscale 2 3 1\nmesh quad.obj\n"
        "popTransform\n");
    EXPECT_EQ(s->primitives.triangleCount(), 2u);
    // quad.obj is the unit square; placed, it spans x 5..7, y 0..3 at z = 1.
    auto hit = down(*s, 6.9, 2.9);
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->p.z, 1, 1e-12);
    expectNear(s->materials[hit->material].diffuse, {0.1, 0.2, 0.3});
    EXPECT_FALSE(down(*s, 7.1, 1));
    EXPECT_FALSE(down(*s, 0.5, 0.5, 0));  // not at the origin any more
}

TEST(CourseMeshes, TheSameMeshTwiceIsStoredOnceAndInstanced) {
    auto s = parseIn("mesh quad.obj\ntranslate 10 0 0\nmesh quad.obj\n");
    EXPECT_EQ(s->primitives.triangleCount(), 0u);
    EXPECT_EQ(s->primitives.instanceCount(), 2u);
    EXPECT_EQ(s->sharedTriangleCount(), 2u);
    EXPECT_EQ(s->primitives.instancedTriangleCount(), 4u);
    EXPECT_TRUE(down(*s, 0.5, 0.5));
    EXPECT_TRUE(down(*s, 10.5, 0.5));
    EXPECT_FALSE(down(*s, 5.5, 0.5));
}

class CourseMeshFiles : public test::TempDirTest {};

TEST_F(CourseMeshFiles, DegenerateTrianglesAreReportedOnceAtTheFirstMeshCommand) {
    // One face of zero area (collinear corners) and one proper face; placed twice (instanced).
    std::ofstream(path("line.obj")) << "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 4\n";
    std::vector<Diagnostic> warnings;
    auto scene =
        parseCourseScene(std::string("mesh line.obj\ntranslate 5 0 0\nmesh line.obj\n") + kCamera,
                         path("scene.test"), warnings);
    EXPECT_EQ(scene->primitives.instanceCount(), 2u);
    EXPECT_EQ(scene->sharedTriangleCount(), 1u);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_EQ(warnings[0].loc.line, 1);
    EXPECT_EQ(warnings[0].message,
              "mesh 'line.obj': 1 triangles have zero area once placed and are skipped (reported "
              "once)");
}

TEST(CourseMeshes, AMeshPlacedOnceIsFlattened) {
    auto s = parseIn("mesh quad.obj\n");
    EXPECT_EQ(s->primitives.triangleCount(), 2u);
    EXPECT_EQ(s->primitives.instanceCount(), 0u);
}

TEST(CourseMeshes, PlacementsUnderDifferentDefaultMaterialsAreNotShared) {
    // quad.obj has no MTL materials: each placement's triangles take the current material.
    auto s = parseIn(
        "diffuse 1 0 0\nmesh quad.obj\ntranslate 10 0 0\ndiffuse 0 1 0\n"
        "mesh quad.obj\ntranslate 10 0 0\nmesh quad.obj\n");
    EXPECT_EQ(s->primitives.triangleCount(), 2u);  // the red one
    EXPECT_EQ(s->primitives.instanceCount(), 2u);  // the two green ones
    expectNear(s->materials[down(*s, 0.5, 0.5)->material].diffuse, {1, 0, 0});
    expectNear(s->materials[down(*s, 10.5, 0.5)->material].diffuse, {0, 1, 0});
    expectNear(s->materials[down(*s, 20.5, 0.5)->material].diffuse, {0, 1, 0});
}

TEST(CourseMeshes, MtlMaterialsOverrideTheCurrentMaterialPerGroup) {
    auto s = parseIn("diffuse 0.3 0.3 0.9\nmesh groups.obj\nsphere 0 0 -20 1\n");
    auto diffuseAt = [&](double x) { return s->materials[down(*s, x, 0.2)->material].diffuse; };
    expectNear(diffuseAt(0.2), {0.3, 0.3, 0.9});  // before any usemtl: the scene's material
    expectNear(diffuseAt(2.2), {0.8, 0.1, 0.1}, 1e-6);
    expectNear(diffuseAt(4.2), {0.1, 0.8, 0.1}, 1e-6);
    // The sphere after the mesh still has the scene's material.
    auto sphere = shoot(*s, {0, 0, -10}, {0, 0, -1});
    ASSERT_TRUE(sphere);
    expectNear(s->materials[sphere->material].diffuse, {0.3, 0.3, 0.9});
}

TEST(CourseMeshes, TextureAppliesToMeshesWithCoordinates) {
    auto s = parseIn("texture quadrants.png clamp\ndiffuse 1 1 1\nmesh uvquad.obj\n");
    auto hit = down(*s, -0.5, 0.5);
    ASSERT_TRUE(hit);
    ASSERT_TRUE(hit->hasUv);
    const Material& m = s->materials[hit->material];
    ASSERT_NE(m.texture, 0u);
    const Texture& t = s->texture(m.texture);
    EXPECT_EQ(t.wrap, TextureWrap::Clamp);
    expectNear(t.eval(true, hit->u, hit->v, hit->p, m.diffuse), {1, 0, 0});
}

TEST(CourseMeshes, TextureNoneAndWrapModes) {
    auto s = parseIn(
        "texture quadrants.png\nmesh uvquad.obj\ntexture none\ntranslate 5 0 0\n"
        "mesh uvquad.obj\n");
    const Material& first = s->materials[down(*s, 0, 0)->material];
    ASSERT_NE(first.texture, 0u);
    EXPECT_EQ(s->texture(first.texture).wrap, TextureWrap::Repeat);
    EXPECT_EQ(s->materials[down(*s, 5, 0)->material].texture, 0u);
}

TEST(CourseMeshes, PhysicallyBasedMapsAndMetalnessMakeAPbrMaterial) {
    auto s = parseIn(
        "diffuse 0.8 0.5 0.2\nroughness 0.25\nmetallic 1\n"
        "texture roughnessmap quadrants.png mirror\ntexture normalmap quadrants.png\n"
        "mesh uvquad.obj\ntexture roughnessmap none\ntranslate 5 0 0\nmesh uvquad.obj\n");
    const Material& m = s->materials[down(*s, 0, 0)->material];
    ASSERT_NE(m.pbr, 0u);
    const PbrMaterial& p = s->pbr(m.pbr);
    expectNear(p.baseColor, {0.8, 0.5, 0.2});
    EXPECT_EQ(p.metallic, 1);
    EXPECT_NEAR(p.roughness, 0.5, 1e-12);  // roughness gives GGX alpha: sqrt(0.25)
    ASSERT_TRUE(p.roughnessTexture);
    EXPECT_FALSE(p.roughnessTexture.image->srgb);  // maps of data are linear
    EXPECT_EQ(p.roughnessTexture.wrapS, TextureWrap::MirroredRepeat);
    ASSERT_TRUE(p.normalTexture);
    EXPECT_TRUE(p.doubleSided);
    const Material& second = s->materials[down(*s, 5, 0)->material];
    ASSERT_NE(second.pbr, 0u);
    EXPECT_FALSE(s->pbr(second.pbr).roughnessTexture);
    EXPECT_TRUE(s->pbr(second.pbr).normalTexture);
}

TEST(CourseMeshes, PhysicallyBasedMapErrorsPointAtTheirToken) {
    expectError("texture normalmap\n", 1, 9, "needs a file or none");
    expectError("texture roughnessmap a.png sideways\n", 1, 28, "unknown texture wrap");
    expectError("metallic 2\n", 1, 10, "metallic must be between 0 and 1");
}

TEST(CourseMeshes, LayerCommandsSetTheExtensionsOfTheCurrentMaterial) {
    auto s = parseIn(
        "diffuse 0.8 0.5 0.2\nclearcoat 0.7 0.2\nsheen 0.5 0.4 0.3 0.6\n"
        "specularfactor 0.5 2 1 0.5\nanisotropy 0.8 90\niridescence 1 1.4 550\n"
        "diffusetransmission 0.3 1 0.5 0\nmesh uvquad.obj\n");
    const Material& m = s->materials[down(*s, 0, 0)->material];
    ASSERT_NE(m.pbr, 0u);  // any layer makes the material physically based
    const PbrMaterial& p = s->pbr(m.pbr);
    EXPECT_EQ(p.clearcoat, 0.7);
    EXPECT_EQ(p.clearcoatRoughness, 0.2);
    expectNear(p.sheenColor, {0.5, 0.4, 0.3});
    EXPECT_EQ(p.sheenRoughness, 0.6);
    EXPECT_EQ(p.specular, 0.5);
    expectNear(p.specularColor, {2, 1, 0.5});  // a colour above 1 scales f0 (clamped after)
    EXPECT_EQ(p.anisotropy, 0.8);
    EXPECT_NEAR(p.anisotropyRotation, std::numbers::pi / 2, 1e-12);
    EXPECT_EQ(p.iridescence, 1);
    EXPECT_EQ(p.iridescenceIor, 1.4);
    EXPECT_EQ(p.iridescenceThicknessMax, 550);
    EXPECT_EQ(p.diffuseTransmission, 0.3);
    expectNear(p.diffuseTransmissionColor, {1, 0.5, 0});
}

TEST(CourseMeshes, LayerCommandErrorsPointAtTheirToken) {
    expectError("clearcoat 1.5\n", 1, 11, "clearcoat must be between 0 and 1");
    expectError("sheen 1 1 2\n", 1, 11, "sheen colour must be between 0 and 1");
    expectError("specularfactor 1 1 1\n", 1, 20, "specularfactor takes a factor");
    expectError("iridescence 1 0.5\n", 1, 15, "index must be between 1 and 4");
    expectError("diffusetransmission -1\n", 1, 21, "must be between 0 and 1");
}

TEST(CourseMeshes, ImageTexturesOnSurfacesWithoutCoordinatesWarnAtTheTextureLine) {
    std::vector<Diagnostic> warnings;
    auto s = parseIn("texture quadrants.png\nsphere 0 0 0 1\nsphere 3 0 0 1\nmesh uvquad.obj\n",
                     &warnings);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_EQ(warnings[0].loc.line, 1);
    EXPECT_EQ(warnings[0].loc.column, 9);
    EXPECT_THAT(warnings[0].message, HasSubstr("2 surfaces show the diffuse colour"));
}

TEST(CourseMeshes, CheckerUsesCoordinatesOnMeshesAndWorldCellsElsewhere) {
    auto s = parseIn("checker 1 1 1 0 0 0 0.5\nmesh uvquad.obj\nplane 0 -2 0 0 1 0\n");
    auto colourAt = [&](const SurfaceInteraction& si) {
        const Material& m = s->materials[si.material];
        return s->texture(m.texture).eval(si.hasUv, si.u, si.v, si.p, m.diffuse);
    };
    // On the square, uv cells of 0.5: the bottom-left quarter (uv < 0.5) is white.
    expectNear(colourAt(*down(*s, -0.5, -0.5)), {1, 1, 1});
    expectNear(colourAt(*down(*s, 0.5, -0.5)), {0, 0, 0});
    // On the plane y = -2 (no uv): world cells of 0.5 centred on multiples of 0.5.
    auto floorAt = [&](double x, double z) { return *shoot(*s, {x, 5, z}, {0, -1, 0}); };
    expectNear(colourAt(floorAt(3, 3)), {1, 1, 1});
    expectNear(colourAt(floorAt(3.5, 3)), {0, 0, 0});
}

TEST(CourseMeshes, CheckerShadesARender) {
    auto s = parseIn(
        "ambient 0 0 0\ndiffuse 0 0 0\nchecker 0.8 0.2 0.2 0.1 0.1 0.6 1\n"
        "directional 0 1 0 1 1 1\nplane 0 0 0 0 1 0\n");
    s->prepare();
    RayCounts counts;
    WhittedIntegrator w(*s);
    Vec3 a = w.radiance(Ray{{0.1, 3, 0.1}, {0, -1, 0}}, 0, counts);
    Vec3 b = w.radiance(Ray{{1.1, 3, 0.1}, {0, -1, 0}}, 0, counts);
    expectNear(a, {0.8, 0.2, 0.2});
    expectNear(b, {0.1, 0.1, 0.6});
}

TEST(CourseMeshes, Errors) {
    Diagnostic d = errorIn("sphere 0 0 0 1\nmesh nowhere.obj\n");
    EXPECT_EQ(d.loc.file, kSceneFile);
    EXPECT_EQ(d.loc.line, 2);
    EXPECT_EQ(d.loc.column, 6);
    EXPECT_THAT(d.message, HasSubstr("cannot read mesh 'nowhere.obj'"));
    EXPECT_THAT(d.message, HasSubstr("No such file or directory"));
    // An error inside the mesh names the mesh file and its line.
    Diagnostic inside = errorIn("mesh out-of-range.obj\n");
    EXPECT_EQ(inside.loc.file, kDir + "out-of-range.obj");
    EXPECT_EQ(inside.loc.line, 5);
    // Placed beyond the coordinate range: at the scene's mesh line.
    Diagnostic far = errorIn("scale 1e18 1e18 1e18\nscale 10 10 10\nmesh quad.obj\n");
    EXPECT_EQ(far.loc.line, 3);
    EXPECT_THAT(far.message, HasSubstr("mesh 'quad.obj': vertex 2 lies beyond"));
    Diagnostic tex = errorIn("texture nowhere.png\n");
    EXPECT_EQ(tex.loc.line, 1);
    EXPECT_EQ(tex.loc.column, 9);
    EXPECT_THAT(tex.message, HasSubstr("cannot read texture"));
    EXPECT_THAT(errorIn("texture quad.obj\n").message, HasSubstr("cannot read texture"));
    Diagnostic wrap = errorIn("texture quadrants.png sideways\n");
    EXPECT_EQ(wrap.loc.column, 23);
    EXPECT_THAT(wrap.message,
                HasSubstr("unknown texture wrap 'sideways' (repeat, clamp or mirror)"));
    EXPECT_THAT(errorIn("texture none clamp\n").message, HasSubstr("takes no other argument"));
    EXPECT_THAT(errorIn("texture\n").message,
                HasSubstr("texture expects 1 to 3 arguments ([slot] file [repeat|clamp|mirror], "
                          "or [slot] none)"));
    EXPECT_THAT(errorIn("checker 1 1 1 0 0 0\n").message,
                HasSubstr("checker expects 7 arguments (r1 g1 b1 r2 g2 b2 scale), got 6"));
    Diagnostic scale = errorIn("checker 1 1 1 0 0 0 0\n");
    EXPECT_EQ(scale.loc.column, 21);
    EXPECT_THAT(scale.message, HasSubstr("checker scale must be positive"));
    EXPECT_THAT(errorIn("mesh\n").message, HasSubstr("mesh expects 1 argument (file.obj), got 0"));
}

TEST(CourseMeshes, ReadingFilesCanBeTurnedOff) {
    LoadLimits noFiles;
    noFiles.readFiles = false;
    EXPECT_THAT(errorIn("mesh quad.obj\n", noFiles).message, HasSubstr("reading files is off"));
    EXPECT_THAT(errorIn("texture quadrants.png\n", noFiles).message,
                HasSubstr("reading files is off"));
    auto s = parseIn("checker 1 1 1 0 0 0 1\nsphere 0 0 0 1\n", nullptr, noFiles);
    EXPECT_EQ(s->textures.size(), 1u);
}

}  // namespace
}  // namespace glint
