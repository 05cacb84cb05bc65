// The integrator seam (render/integrators/integrator.h): integrators by name, the one repair of non-finite
// radiance every integrator's result passes through, and the renderer calling the integrator
// the scene names.

#include "glint/render/integrators/integrator.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "glint/core/error.h"
#include "glint/render/renderer.h"
#include "unit/test_support.h"

namespace glint {
namespace {

TEST(Integrators, WhittedIsTheDefaultAndFirst) {
    ASSERT_FALSE(integrators().empty());
    EXPECT_EQ(integrators().front().name, "whitted");
    EXPECT_EQ(Scene().integrator, "whitted");
    EXPECT_NE(findIntegrator("whitted"), nullptr);
    EXPECT_EQ(findIntegrator("Whitted"), nullptr);  // names are exact
    EXPECT_EQ(findIntegrator(""), nullptr);
    EXPECT_NE(integratorNameList().find("whitted"), std::string::npos);
}

Scene& oneSphere(Scene& scene) {
    scene.width = scene.height = 5;
    scene.camera = CameraSpec{{0, 0, 4}, {0, 0, 0}, {0, 1, 0}, 45};
    scene.primitives.addSphere(Sphere{{0, 0, 0}, 1, {}},
                               scene.addMaterial(test::makeMaterial({0.25, 0.5, 0.75})));
    scene.prepare();
    return scene;
}

TEST(Integrators, TheRendererUsesTheIntegratorTheSceneNames) {
    Scene scene;
    oneSphere(scene);
    RenderOptions o;
    o.threads = 1;
    EXPECT_EQ(render(scene, o).film.at(2, 2), Vec3(0.25, 0.5, 0.75));  // ambient, by Whitted

    scene.integrator = "no-such-integrator";
    try {
        render(scene, o);
        FAIL() << "an unknown integrator rendered";
    } catch (const RenderError& e) {
        EXPECT_NE(std::string(e.what()).find("unknown integrator 'no-such-integrator'"),
                  std::string::npos)
            << e.what();
        EXPECT_NE(std::string(e.what()).find("whitted"), std::string::npos) << e.what();
    }
}

TEST(Integrators, MadeByNameTheyShadeACameraRayGivenItsHit) {
    Scene scene;
    oneSphere(scene);
    std::unique_ptr<Integrator> whitted = makeIntegrator(scene, {});
    ASSERT_NE(whitted, nullptr);
    EXPECT_FALSE(whitted->usesRandomNumbers());  // no area lights, no rough materials
    Ray ray{{0, 0, 4}, {0, 0, -1}};
    Hit hit;
    ASSERT_TRUE(scene.bvh().intersect(ray, hit));
    RayCounts counts;
    PathContext ctx{Rng(), counts};
    EXPECT_EQ(whitted->li(ray, &hit, ctx), Vec3(0.25, 0.5, 0.75));
    EXPECT_EQ(whitted->li(ray, nullptr, ctx), Vec3(0));  // the black background
    EXPECT_EQ(counts.camera, 0u);                        // the caller traced the camera ray
}

TEST(FiniteRadiance, PassesFiniteValuesUnchangedAndUncounted) {
    RayCounts counts;
    Vec3 c(0.5, -2, 1e29);
    EXPECT_EQ(finiteRadiance(c, counts), c);
    EXPECT_EQ(counts.nonFinite, 0u);
}

TEST(FiniteRadiance, ClampsHugeFiniteValuesWithoutCountingThem) {
    RayCounts counts;
    EXPECT_EQ(finiteRadiance(Vec3(1e300, -1e300, 0), counts), Vec3(kMaxRadiance, -kMaxRadiance, 0));
    EXPECT_EQ(counts.nonFinite, 0u);
}

TEST(FiniteRadiance, RepairsAndCountsNaNAndInfinity) {
    constexpr double nan = std::numeric_limits<double>::quiet_NaN();
    constexpr double inf = std::numeric_limits<double>::infinity();
    RayCounts counts;
    EXPECT_EQ(finiteRadiance(Vec3(nan, 1, 2), counts), Vec3(0, 1, 2));
    EXPECT_EQ(counts.nonFinite, 1u);
    EXPECT_EQ(finiteRadiance(Vec3(1, inf, -inf), counts), Vec3(1, kMaxRadiance, -kMaxRadiance));
    EXPECT_EQ(counts.nonFinite, 2u);  // one value, however many channels
}

TEST(RayCounts, AddUpEveryKind) {
    RayCounts a{1, 2, 3, 4}, b{10, 20, 30, 40};
    a += b;
    EXPECT_EQ(a.camera, 11u);
    EXPECT_EQ(a.shadow, 22u);
    EXPECT_EQ(a.reflection, 33u);
    EXPECT_EQ(a.nonFinite, 44u);
    EXPECT_EQ(a.total(), 66u);  // rays only
}

}  // namespace
}  // namespace glint
