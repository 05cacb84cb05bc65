// The shadow catcher (render/integrators/shadow_catcher.h): the irradiance it divides by, where
// rays meet it, exactly the environment where nothing is in the way, and the fraction of light a
// square above it blocks (its form factor, known in closed form) in the mean of many samples; in
// the path tracer, camera rays see it and no other ray does.

#include "glint/render/integrators/shadow_catcher.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "glint/math/rng.h"
#include "glint/render/integrators/path.h"
#include "glint/scene/pbr_material.h"
#include "unit/statistics.h"

namespace glint {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kZ = 5;

/// A map of constant radiance `c`.
std::shared_ptr<const EnvironmentMap> constantMap(double c) {
    return std::make_shared<const EnvironmentMap>(8, 4, std::vector<float>(96, float(c)));
}

/// A square of half-size `a` at height `h` centred above the origin, facing down and up.
void addSquare(Scene& scene, double a, double h) {
    Material m;
    m.diffuse = Vec3(0.5);
    uint32_t id = scene.addMaterial(m);
    scene.primitives.addTriangle({-a, h, -a}, {a, h, -a}, {a, h, a}, nullptr, id);
    scene.primitives.addTriangle({-a, h, -a}, {a, h, a}, {-a, h, a}, nullptr, id);
}

/// The fraction of an upward plane's cosine-weighted hemisphere that a square of half-size a
/// at height h straight above it covers: four times the form factor from a point under the
/// corner of an a x a rectangle (Siegel and Howell's closed form).
double squareFormFactor(double a, double h) {
    double x = a / h, y = a / h, sx = std::sqrt(1 + x * x), sy = std::sqrt(1 + y * y);
    double corner = (x / sx * std::atan(y / sx) + y / sy * std::atan(x / sy)) / (2 * kPi);
    return 4 * corner;
}

Point2 uniform2(Rng& rng) {
    return {static_cast<double>(rng.uniform()), static_cast<double>(rng.uniform())};
}

TEST(ShadowCatcher, DividesByTheIrradianceOfTheUpperHemisphere) {
    Scene scene;
    scene.environment = constantMap(0.5);
    EXPECT_NEAR(upwardIrradiance(scene).y, 0.5 * kPi, 1e-12);
    scene.environment = std::make_shared<const EnvironmentMap>(
        8, 4, std::vector<float>(96, 0.5f), 3.0, 40.0);  // the scale counts, the turn does not
    EXPECT_NEAR(upwardIrradiance(scene).y, 1.5 * kPi, 1e-12);
    // Light from below counts for nothing: a map bright in its lower half only.
    std::vector<float> lower(96, 0.0f);
    for (size_t i = 48; i < 96; ++i) lower[i] = 7;
    scene.environment = std::make_shared<const EnvironmentMap>(8, 4, lower);
    EXPECT_EQ(upwardIrradiance(scene), Vec3(0));
    // The gradient background, against a quadrature of it.
    scene.environment = nullptr;
    scene.background = Background{{0.2, 0.4, 0.6}, {1, 0.5, 0}};
    Vec3 sum(0);
    const int n = 2000;
    for (int i = 0; i < n; ++i) {  // d omega cos = 2 pi cos sin d theta over the upper half
        double theta = (i + 0.5) / n * kPi / 2;
        sum += scene.background.eval({std::sin(theta), std::cos(theta), 0}) *
               (2 * kPi * std::cos(theta) * std::sin(theta) * (kPi / 2 / n));
    }
    Vec3 e = upwardIrradiance(scene);
    EXPECT_NEAR(e.x, sum.x, 1e-6);
    EXPECT_NEAR(e.y, sum.y, 1e-6);
    EXPECT_NEAR(e.z, sum.z, 1e-6);
}

TEST(ShadowCatcher, SamplesTheUpperHemisphereByRadianceTimesCosine) {
    // L cos(theta) / pdf averages to the irradiance (the density is right), and varies little
    // (the density follows L cos(theta)), for maps of even and odd height, turned or not, and
    // for the background.
    std::vector<float> rgb;
    const int w = 16, h = 9;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c)
                rgb.push_back(x == 3 && y == 2 ? 50.0f : float(0.2 + 0.05 * ((x + y) % 4)));
    std::vector<std::shared_ptr<const EnvironmentMap>> maps = {
        std::make_shared<const EnvironmentMap>(w, h, rgb),
        std::make_shared<const EnvironmentMap>(w, h, rgb, 2.0, 75.0),
        std::make_shared<const EnvironmentMap>(w, h - 1,
                                               std::vector<float>(rgb.begin(), rgb.end() - 48)),
        nullptr};
    for (const auto& map : maps) {
        Scene scene;
        scene.shadowCatcher = ShadowCatcher{0};
        scene.environment = map;
        scene.background = Background{{0.1, 0.1, 0.1}, {0.9, 0.9, 0.9}};
        scene.prepare();
        ShadowCatcherShading catcher(scene);
        Rng rng(12);
        test::MeanEstimate e;
        for (int i = 0; i < 40000; ++i) {
            auto s = catcher.sampleEnvironment(uniform2(rng));
            if (!s) {
                e.add(0);
                continue;
            }
            EXPECT_GT(s->wi.y, 0);
            e.add(s->L.y * s->wi.y / s->pdf);
        }
        const double E = catcher.environmentIrradiance().y;
        EXPECT_NEAR(e.mean(), E, kZ * e.standardError() + 1e-3 * E);
        if (!map) continue;
        // Much less spread than sampling by cos(theta) alone, which rarely finds the bright
        // texel.
        test::MeanEstimate cosine;
        for (int i = 0; i < 40000; ++i) {
            Vec3 d = sampleCosineHemisphere(uniform2(rng));
            cosine.add(map->eval({d.x, d.z, -d.y}).y * kPi);
        }
        EXPECT_NEAR(cosine.mean(), E, kZ * cosine.standardError() + 1e-3 * E);
        EXPECT_LT(e.standardError(), 0.3 * cosine.standardError());
    }
}

TEST(ShadowCatcher, IsMetFromAboveOnly) {
    Scene scene;
    scene.shadowCatcher = ShadowCatcher{0.5};
    scene.environment = constantMap(1);
    scene.prepare();
    ShadowCatcherShading catcher(scene);
    EXPECT_EQ(catcher.intersect(Ray{{0, 1.5, 0}, {0, -1, 0}, 0, kInfinity}), 1.0);
    std::optional<double> t = catcher.intersect(Ray{{0, 2.5, 0}, {0.6, -0.8, 0}, 0, kInfinity});
    ASSERT_TRUE(t);
    EXPECT_NEAR(*t, 2.5, 1e-12);
    EXPECT_FALSE(catcher.intersect(Ray{{0, 1.5, 0}, {0, 1, 0}, 0, kInfinity}));  // upwards
    EXPECT_FALSE(catcher.intersect(Ray{{0, 0, 0}, {0, -1, 0}, 0, kInfinity}));   // from below
    EXPECT_FALSE(catcher.intersect(Ray{{0, 1.5, 0}, {1, 0, 0}, 0, kInfinity}));  // level
    EXPECT_FALSE(catcher.intersect(Ray{{0, 1.5, 0}, {0, -1, 0}, 0, 0.9}));       // too short
}

TEST(ShadowCatcher, ShowsTheEnvironmentExactlyWhereNothingIsInTheWay) {
    Scene scene;
    scene.shadowCatcher = ShadowCatcher{0};
    std::vector<float> sky;
    for (int i = 0; i < 16 * 8; ++i)
        for (int c = 0; c < 3; ++c) sky.push_back(float(0.1 + 0.05 * (i % 7) + 0.1 * c));
    scene.environment = std::make_shared<const EnvironmentMap>(16, 8, sky);
    Material m;
    scene.primitives.addSphere(Sphere{{0, -5, 0}, 1, {}}, scene.addMaterial(m));  // below it
    scene.prepare();
    ShadowCatcherShading catcher(scene);
    Rng rng(3);
    for (int i = 0; i < 1000; ++i) {
        Vec3 dir = normalize(Vec3(rng.uniform() - 0.5, -1, rng.uniform() - 0.5));
        RayCounts counts;
        Vec3 L = catcher.radiance({0, 0, 0}, dir, uniform2(rng), rng.uniform(), counts);
        EXPECT_EQ(L, scene.environment->eval(dir));
    }
}

TEST(ShadowCatcher, ASquareAboveBlocksItsFormFactor) {
    // Under a square of half-size 1 at height 1 the plane receives 1 - F of its light, F the
    // square's form factor, whether the environment is a map or the background.
    const double f = squareFormFactor(1, 1);
    for (bool map : {true, false}) {
        Scene scene;
        scene.shadowCatcher = ShadowCatcher{0};
        if (map)
            scene.environment = constantMap(0.8);
        else
            scene.background = Background{Vec3(0.8), Vec3(0.8)};
        addSquare(scene, 1, 1);
        scene.prepare();
        ShadowCatcherShading catcher(scene);
        Rng rng(map ? 5 : 6);
        test::MeanEstimate e;
        const Vec3 dir = normalize(Vec3(0.3, -1, 0.2));
        for (int i = 0; i < 40000; ++i) {
            RayCounts counts;
            e.add(catcher.radiance({0, 0, 0}, dir, uniform2(rng), rng.uniform(), counts).y);
        }
        EXPECT_NEAR(e.mean(), 0.8 * (1 - f), kZ * e.standardError()) << (map ? "map" : "colour");
        EXPECT_GT(f, 0.5);  // the test means something: more than half is blocked
    }
}

TEST(ShadowCatcher, TheSceneLightsCastShadowsToo) {
    // A point light straight above the square, and a dim environment: the light is blocked
    // entirely, the environment by the form factor.
    const double f = squareFormFactor(1, 1), env = 0.1, light = 2;
    Scene scene;
    scene.shadowCatcher = ShadowCatcher{0};
    scene.environment = constantMap(env);
    addSquare(scene, 1, 1);
    LightSpec point;
    point.position = {0, 3, 0};
    point.color = Vec3(light);  // no fall-off: irradiance `light` straight below
    scene.lights.push_back(point);
    scene.prepare();
    ShadowCatcherShading catcher(scene);
    Rng rng(8);
    test::MeanEstimate e;
    for (int i = 0; i < 40000; ++i) {
        RayCounts counts;
        e.add(catcher.radiance({0, 0, 0}, {0, -1, 0}, uniform2(rng), rng.uniform(), counts).y);
    }
    double total = env * kPi + light, blocked = f * env * kPi + light;
    EXPECT_NEAR(e.mean(), env * (1 - blocked / total), kZ * e.standardError());
    // Away from the square, the light reaches the plane: exactly the environment there.
    RayCounts counts;
    EXPECT_EQ(catcher.radiance({100, 0, 0}, {0, -1, 0}, {0.3, 0.6}, 0.5, counts),
              scene.environment->eval({0, -1, 0}));
}

TEST(ShadowCatcher, APointLightInsideItsGlowingBulbCastsNoShadowAroundIt) {
    // A bulb (an emitting sphere) around a bright point light, a dim environment: the light
    // cannot leave the bulb, and the plane around it shows the environment, not a dark halo
    // (issue 37); an ordinary sphere there still shadows it.
    for (bool glows : {true, false}) {
        Scene scene;
        scene.shadowCatcher = ShadowCatcher{0};
        scene.environment = constantMap(0.1);
        Material bulb;
        bulb.diffuse = Vec3(0.5);
        if (glows) bulb.emission = Vec3(3);
        scene.primitives.addSphere(Sphere{{0, 2, 0}, 0.2, {}}, scene.addMaterial(bulb));
        LightSpec point;
        point.position = {0, 2, 0};
        point.color = Vec3(50);
        scene.lights.push_back(point);
        scene.prepare();
        ShadowCatcherShading catcher(scene);
        Rng rng(3);
        RayCounts counts;
        // Beside the bulb, where the sphere hides almost none of the environment.
        const Vec3 beside(1.5, 0, 0);
        test::MeanEstimate e;
        for (int i = 0; i < 2000; ++i)
            e.add(catcher.radiance(beside, {0, -1, 0}, uniform2(rng), rng.uniform(), counts).y);
        if (glows) {
            EXPECT_GT(e.mean(), 0.099) << "a halo around the bulb";
        } else {
            EXPECT_LT(e.mean(), 0.01) << "the sphere hides the light";
        }
    }
}

TEST(ShadowCatcher, LayersOfAlphaBlendedSurfacesLetThroughTheirShareOfLight) {
    // N wide layers of alpha a above the plane, under the environment and a light straight
    // above: each shadow ray passes a layer with probability 1 - a, so (1 - a)^N of the light
    // arrives, and the plane shows that share of the environment. The layers are wide enough
    // that what they leave uncovered near the horizon is below 1e-4 of the light.
    const double env = 0.5, light = 1, a = 0.3;
    for (int layers : {1, 3}) {
        Scene scene;
        scene.shadowCatcher = ShadowCatcher{0};
        scene.environment = constantMap(env);
        PbrMaterial glassy;
        glassy.alphaMode = AlphaMode::Blend;
        glassy.alpha = a;
        Material m;
        m.pbr = scene.addPbrMaterial(glassy);
        const uint32_t id = scene.addMaterial(m);
        for (int k = 0; k < layers; ++k) {
            const double h = 1 + 0.25 * k, w = 1e3;
            scene.primitives.addTriangle({-w, h, -w}, {w, h, -w}, {w, h, w}, nullptr, id);
            scene.primitives.addTriangle({-w, h, -w}, {w, h, w}, {-w, h, w}, nullptr, id);
        }
        LightSpec point;
        point.position = {0, 3, 0};
        point.color = Vec3(light);
        scene.lights.push_back(point);
        scene.prepare();
        ShadowCatcherShading catcher(scene);
        Rng rng(11 + layers);
        test::MeanEstimate e;
        for (int i = 0; i < 40000; ++i) {
            RayCounts counts;
            // Points spread over the plane, so that the shadow rays differ from sample to sample.
            const Vec3 p(rng.uniform() - 0.5, 0, rng.uniform() - 0.5);
            e.add(catcher.radiance(p, {0, -1, 0}, uniform2(rng), rng.uniform(), counts).y);
        }
        const double through = std::pow(1 - a, layers);
        EXPECT_NEAR(e.mean(), env * through, kZ * e.standardError() + 1e-4) << layers;
        EXPECT_GT(e.mean(), 0.5 * env * through) << layers;  // not the full shadow of before
    }
}

/// A diffuse sphere of albedo 1 resting on a shadow catcher at y = 0 under a uniform
/// environment of radiance 1; `withCatcher` false: the same without it.
void sphereOnTheGround(Scene& scene, bool withCatcher) {
    scene.integrator = "path";
    scene.maxDepth = 64;
    scene.environment = constantMap(1);
    if (withCatcher) scene.shadowCatcher = ShadowCatcher{0};
    Material white;
    white.diffuse = Vec3(1);
    scene.primitives.addSphere(Sphere{{0, 1, 0}, 1, {}}, scene.addMaterial(white));
    scene.prepare();
}

test::MeanEstimate estimate(const Scene& scene, const Ray& ray, int n, uint64_t seed) {
    PathIntegrator integrator(scene);
    Hit hit;
    bool found = scene.bvh().intersect(ray, hit);
    test::MeanEstimate e;
    for (int i = 0; i < n; ++i) {
        RayCounts counts;
        PathContext ctx{Rng(seed + i), counts};
        ctx.pixelSeed = seed;
        ctx.sampleIndex = static_cast<uint32_t>(i);
        e.add(integrator.li(ray, found ? &hit : nullptr, ctx).y);
    }
    return e;
}

TEST(ShadowCatcher, ThePathTracerShowsItToCameraRaysOnly) {
    Scene with, without;
    sphereOnTheGround(with, true);
    sphereOnTheGround(without, false);
    // A camera ray far from the sphere sees the environment, exactly; one next to the contact
    // point sees it darkened by the sphere's form factor from there, (r / d)^2 cos(beta) for a
    // sphere of radius r whose centre is d away, beta from the normal.
    Ray far{{200, 3, 200}, normalize(Vec3(0, -1, 0.1)), 0, kInfinity};
    test::MeanEstimate e = estimate(with, far, 100, 1);
    EXPECT_EQ(e.mean(), 1);
    EXPECT_EQ(e.standardError(), 0);
    Ray near{{1.2, 5, 0}, {0, -1, 0}, 0, kInfinity};
    const double d = std::hypot(1.2, 1.0), formFactor = 1 / (d * d) * (1 / d);
    test::MeanEstimate shadowed = estimate(with, near, 20000, 2);
    EXPECT_NEAR(shadowed.mean(), 1 - formFactor, kZ * shadowed.standardError());
    EXPECT_EQ(estimate(without, near, 10, 3).mean(), 1);  // the environment below
    // The sphere's underside: lit from below as if the catcher were not there (it is a furnace:
    // radiance 1 everywhere on the sphere).
    Ray under{{3, 0.5, 0}, normalize(Vec3(-1, 0.1, 0)), 0, kInfinity};
    test::MeanEstimate a = estimate(with, under, 4000, 4);
    EXPECT_NEAR(a.mean(), 1, kZ * a.standardError() + 1e-9);
}

}  // namespace
}  // namespace glint
