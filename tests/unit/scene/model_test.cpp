// Models, whatever file they came from: placing one in a scene under a transform
// (placeModel), and making a whole scene of one (frameModelScene).

#include "glint/scene/model.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "glint/math/mat4.h"
#include "glint/scene/model_framing.h"
#include "glint/scene/studio_environment.h"
#include "unit/test_support.h"

namespace glint {
namespace {

using test::expectNear;
using ::testing::EndsWith;
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

TEST(CameraChoice, AnOrbitPlacesTheEyeOnASphereAroundTheTarget) {
    CameraChoice c = CameraChoice::parse("orbit:30,60,4.75");
    ASSERT_EQ(c.kind, CameraChoice::Kind::Orbit);
    // The eye of Khronos' AnimatedCube scenario, as gltf-ext/RENDER-FIDELITY.md tabulates it.
    CameraSpec s = c.orbit.spec();
    EXPECT_NEAR(s.eye.x, 2.05681, 1e-5);
    EXPECT_NEAR(s.eye.y, 2.375, 1e-12);
    EXPECT_NEAR(s.eye.z, 3.5625, 1e-12);
    EXPECT_EQ(s.center, Vec3(0, 0, 0));
    EXPECT_EQ(s.up, Vec3(0, 1, 0));
    EXPECT_EQ(s.fovyDegrees, 45);
    // A target moves eye and centre alike; theta 90 puts the eye on +x, phi 100 below.
    s = CameraChoice::parse("orbit:90,100,2,1,-2,0.5").orbit.spec();
    EXPECT_EQ(s.center, Vec3(1, -2, 0.5));
    EXPECT_NEAR(s.eye.x, 1 + 2 * std::sin(100 * std::numbers::pi / 180), 1e-12);
    EXPECT_NEAR(s.eye.y, -2 + 2 * std::cos(100 * std::numbers::pi / 180), 1e-12);
    EXPECT_NEAR(s.eye.z, 0.5, 1e-12);
    EXPECT_EQ(CameraChoice::parse("orbit:-60,90,124,-35,37,25").describe(),
              "the orbit camera theta -60, phi 90, radius 124 around (-35, 37, 25)");
}

TEST(CameraChoice, AMalformedOrbitSaysWhatIsWrong) {
    auto problem = [](const std::string& text) -> std::string {
        try {
            CameraChoice::parse(text);
        } catch (const std::invalid_argument& e) {
            return e.what();
        }
        return "no error";
    };
    EXPECT_THAT(problem("orbit:"), HasSubstr("'' is not a number"));
    EXPECT_THAT(problem("orbit:1,2"), HasSubstr("got 2 numbers"));
    EXPECT_THAT(problem("orbit:1,2,3,4"), HasSubstr("got 4 numbers"));
    EXPECT_THAT(problem("orbit:1,2,3,"), HasSubstr("'' is not a number"));
    EXPECT_THAT(problem("orbit:1,2,3x"), HasSubstr("'3x' is not a number"));
    EXPECT_THAT(problem("orbit:inf,90,1"), HasSubstr("'inf' is not finite"));
    EXPECT_THAT(problem("orbit:0,90,0"), HasSubstr("radius must be positive"));
    EXPECT_THAT(problem("orbit:0,90,nan"), HasSubstr("'nan' is not finite"));
    EXPECT_THAT(problem("orbit:0,0,1"), HasSubstr("phi must be strictly between 0 and 180"));
    EXPECT_THAT(problem("orbit:0,180,1"), HasSubstr("phi must be strictly between 0 and 180"));
    EXPECT_EQ(problem("orbit:0,179.9,1e-3"), "no error");
}

// ---- The classic look (the course's Whitted integrator) ----

TEST(ModelFraming, AModelWithoutCameraOrLightsGetsGlintsAndSaysSo) {
    ModelScene m = frameModelScene(singleMeshModel(triangle()), 0, 0, ModelLook::classic());
    EXPECT_TRUE(m.framed);
    EXPECT_EQ(m.scene->width, 640);
    EXPECT_EQ(m.scene->height, 480);
    ASSERT_TRUE(m.scene->camera);
    EXPECT_EQ(m.scene->lights.size(), 2u);
    EXPECT_EQ(m.scene->primitives.planeCount(), 1u);  // the floor
    EXPECT_THAT(m.note, StartsWith("tri.obj has no camera or lights: framing it with a camera"));
    // The course's settings: nothing of the studio's.
    EXPECT_EQ(m.scene->integrator, "whitted");
    EXPECT_EQ(m.scene->spp, 0);
    EXPECT_FALSE(m.scene->environment);
    EXPECT_FALSE(m.scene->shadowCatcher);
    EXPECT_EQ(m.scene->display, DisplaySpec{});
}

TEST(ModelFraming, TheModelsOwnCameraAndLightsAreKept) {
    Model model = singleMeshModel(triangle());
    model.camera = ModelCamera{{{0, 0, 5}, {0, 0, 0}, {0, 1, 0}, 30}, 2.0, "camera 0 (node 1)"};
    LightSpec light;
    light.position = {0, 0, 3};
    model.lights.push_back(light);
    ModelScene m = frameModelScene(model, 0, 0, ModelLook::classic());
    EXPECT_EQ(m.note, "");  // nothing assumed
    EXPECT_EQ(m.scene->camera->fovyDegrees, 30);
    EXPECT_EQ(m.scene->height, 320);  // 640 wide at the camera's aspect ratio
    ASSERT_EQ(m.scene->lights.size(), 1u);
    EXPECT_EQ(m.scene->lights[0].position, Vec3(0, 0, 3));
    model.lights.clear();
    EXPECT_THAT(frameModelScene(model, 0, 0, ModelLook::classic()).note,
                HasSubstr("has no lights: lighting it with a key and a fill directional light "
                          "(and its camera 0 (node 1))"));
}

TEST(ModelFraming, TheClassicLookTakesTheGroundAndEnvironmentAskedFor) {
    ModelLook look = ModelLook::classic();
    look.ground = ModelGround::None;
    look.environment = std::shared_ptr<const EnvironmentMap>();  // black
    ModelScene m = frameModelScene(singleMeshModel(triangle()), 0, 0, look);
    EXPECT_EQ(m.scene->primitives.planeCount(), 0u);
    EXPECT_EQ(m.scene->backgroundRadiance({0, 1, 0}), Vec3(0));
    EXPECT_THAT(m.note, HasSubstr("(fovy 40), a key and a fill directional light and a light "
                                  "grey material"));
}

TEST(ModelFraming, AModelOfNothingVisibleIsAnError) {
    MeshData flat = triangle();
    flat.positions[2] = {2, 0, 0};  // zero area
    EXPECT_THROW(frameModelScene(singleMeshModel(flat)), SceneError);
    EXPECT_THROW(frameModelScene(singleMeshModel(flat), 0, 0, ModelLook::classic()), SceneError);
}

// ---- The studio look (the default) ----

TEST(ModelFraming, TheStudioLookPathTracesInTheStudioOnAGroundShadow) {
    ModelScene m = frameModelScene(singleMeshModel(triangle()));
    const Scene& scene = *m.scene;
    EXPECT_TRUE(m.framed);
    EXPECT_EQ(scene.integrator, "path");
    EXPECT_EQ(scene.spp, kStudioSpp);
    EXPECT_EQ(scene.maxDepth, kStudioMaxDepth);
    EXPECT_EQ(scene.environment.get(), studioEnvironment().get());
    EXPECT_EQ(scene.display, (DisplaySpec{ToneMap::PbrNeutral, true}));
    // The ground: a shadow catcher a thousandth of the model's size under its lowest point (the
    // triangle's bounding sphere has radius sqrt(2) / 2), and no plane or light of Glint's.
    ASSERT_TRUE(scene.shadowCatcher);
    EXPECT_NEAR(scene.shadowCatcher->height, -1e-3 * std::sqrt(0.5), 1e-9);
    EXPECT_EQ(scene.primitives.planeCount(), 0u);
    EXPECT_TRUE(scene.lights.empty());
    ASSERT_TRUE(scene.camera);
    EXPECT_THAT(m.note, StartsWith("tri.obj has no camera: framing it with a camera at ("));
    EXPECT_THAT(m.note, HasSubstr("(fovy 40), and showing it in the studio environment with a "
                                  "ground shadow at y = -0.0007071"));
}

TEST(ModelFraming, TheStudioAddsToTheModelsOwnCameraAndLights) {
    Model model = singleMeshModel(triangle());
    model.camera = ModelCamera{{{0, 0, 5}, {0, 0, 0}, {0, 1, 0}, 30}, 2.0, "camera 0 (node 1)"};
    LightSpec light;
    light.position = {0, 0, 3};
    model.lights.push_back(light);
    ModelScene m = frameModelScene(model);
    EXPECT_EQ(m.scene->camera->fovyDegrees, 30);
    ASSERT_EQ(m.scene->lights.size(), 1u);  // its own, and the environment
    EXPECT_TRUE(m.scene->environment);
    EXPECT_TRUE(m.scene->shadowCatcher);
    EXPECT_EQ(m.note,
              "showing tri.obj in the studio environment with a ground shadow at y = -0.0007071 "
              "(and its camera 0 (node 1) and 1 light of its own)");
}

TEST(ModelFraming, LightsInPhysicalUnitsGetAnExposureThatBringsThemToTheStudiosLevel) {
    // A light's colour is physical (radiant intensity, irradiance): a white matte surface
    // facing it shows colour / pi / d^2, which is compared with the studio's radiance.
    const double studio = std::numbers::pi * luminance(studioEnvironment()->averageRadiance());
    auto sun = [](double level) {
        LightSpec l;
        l.kind = LightSpec::Kind::Directional;
        l.direction = {0, 1, 0};
        l.color = Vec3(level);
        return l;
    };
    Scene scene;
    scene.lights = {sun(100 * studio)};  // 100 times the studio: 2^-6.64, to the half stop
    EXPECT_EQ(modelExposure(scene, Vec3(0), 1), -6.5);
    scene.lights = {sun(3 * studio)};  // a file lit about as brightly as the studio: as it is
    EXPECT_EQ(modelExposure(scene, Vec3(0), 1), 0);
    // A point light by the inverse square from where it is measured (not nearer than a
    // quarter of the model's size).
    LightSpec bulb;
    bulb.position = {0, 2, 0};
    bulb.attenuation = {0, 0, 1};
    bulb.color = Vec3(4 * 64 * studio);
    scene.lights = {bulb};
    EXPECT_EQ(modelExposure(scene, Vec3(0), 1), -6);
    EXPECT_EQ(modelExposure(scene, Vec3(0, 2, 0), 4), -8);  // counted from 1 away
    // Inside a glowing bulb it lights nothing outside: it counts for nothing.
    Material glass;
    glass.emission = Vec3(5);
    scene.primitives.addSphere(Sphere{{0, 2, 0}, 0.1, {}}, scene.addMaterial(glass));
    EXPECT_EQ(modelExposure(scene, Vec3(0), 1), 0);

    // The studio look chooses it, says so, and shows the scene at it.
    Model model = singleMeshModel(triangle());
    model.lights.push_back(sun(1000 * studio));
    ModelScene m = frameModelScene(model);
    EXPECT_EQ(m.scene->display.exposure, -10);
    EXPECT_THAT(m.note, HasSubstr("its lights are in physical units (candela, lux), 1024 times "
                                  "as bright as the studio: exposure -10 (--exposure changes it)"));
}

TEST(ModelFraming, EachStudioDefaultCanBeTurnedOff) {
    ModelLook look;
    look.ground = ModelGround::None;
    ModelScene none = frameModelScene(singleMeshModel(triangle()), 0, 0, look);
    EXPECT_FALSE(none.scene->shadowCatcher);
    EXPECT_EQ(none.scene->primitives.planeCount(), 0u);
    EXPECT_THAT(none.note, EndsWith("showing it in the studio environment"));

    look.ground = ModelGround::Floor;
    ModelScene floor = frameModelScene(singleMeshModel(triangle()), 0, 0, look);
    EXPECT_FALSE(floor.scene->shadowCatcher);
    EXPECT_EQ(floor.scene->primitives.planeCount(), 1u);
    EXPECT_THAT(floor.note, HasSubstr("in the studio environment on a grey floor at y = "));

    // Another map, or none: then a key and a fill light, since nothing else would light it.
    look = ModelLook{};
    auto sky = std::make_shared<const EnvironmentMap>(2, 1, std::vector<float>(6, 0.5f));
    look.environment = sky;
    ModelScene mapped = frameModelScene(singleMeshModel(triangle()), 0, 0, look);
    EXPECT_EQ(mapped.scene->environment.get(), sky.get());
    EXPECT_TRUE(mapped.scene->lights.empty());
    EXPECT_THAT(mapped.note, HasSubstr("in the environment map with a ground shadow"));
    look.environment = std::shared_ptr<const EnvironmentMap>();
    ModelScene dark = frameModelScene(singleMeshModel(triangle()), 0, 0, look);
    EXPECT_FALSE(dark.scene->environment);
    EXPECT_EQ(dark.scene->lights.size(), 2u);
    EXPECT_THAT(dark.note, HasSubstr("in the dark, lit by a key and a fill directional light, "
                                     "with a ground shadow"));
    // A model that glows lights itself: no key and fill light is added to it in the dark.
    MeshData glowing = triangle();
    MeshMaterial panel;
    panel.name = "panel";
    panel.material.emission = Vec3(2);
    glowing.materials = {panel};
    glowing.triangles[0].material = 0;
    ModelScene lamp = frameModelScene(singleMeshModel(glowing), 0, 0, look);
    EXPECT_TRUE(lamp.scene->lights.empty());
    EXPECT_THAT(lamp.note, HasSubstr("in the dark with a ground shadow"));
}

}  // namespace
}  // namespace glint
