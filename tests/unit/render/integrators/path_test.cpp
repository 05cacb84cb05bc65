// The path tracer (render/integrators/path.h) against cases with known answers: white furnaces, the
// inside of a closed emitting sphere, and the agreement of its light-sampling, BSDF-sampling
// and combined (MIS) estimators. Each estimate is the mean of many independent camera samples
// with its standard error; a test fails when the answer lies more than kZ standard errors
// away (two-sided p < 6e-7 per comparison, so a false failure among a few hundred comparisons
// has probability below 2e-4), plus a small allowance for the truncation at maxdepth where
// there is one.

#include "glint/render/integrators/path.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>

#include "glint/core/spawn.h"
#include "unit/statistics.h"

namespace glint {
namespace {

constexpr double kZ = 5;

/// The path tracer's radiance along `ray`, averaged over `n` samples (green channel, or the
/// channel `c`), each sample with its own seed as the renderer gives them.
test::MeanEstimate estimate(const Scene& scene, const Integrator& integrator, const Ray& ray, int n,
                            uint64_t pixelSeed, int c = 1) {
    test::MeanEstimate e;
    Hit hit;
    bool found = scene.bvh().intersect(ray, hit);
    for (int i = 0; i < n; ++i) {
        RayCounts counts;
        PathContext ctx{Rng(pixelSeed + i), counts};
        ctx.pixelSeed = pixelSeed;
        ctx.sampleIndex = static_cast<uint32_t>(i);
        Vec3 L = integrator.li(ray, found ? &hit : nullptr, ctx);
        EXPECT_EQ(counts.nonFinite, 0u);
        e.add(c == 0 ? L.x : c == 1 ? L.y : L.z);
    }
    return e;
}

/// Rays from (0, 0, 4) towards points spread over the unit sphere's disk as seen from there.
std::vector<Ray> raysAtTheSphere(int count) {
    std::vector<Ray> rays;
    for (int i = 0; i < count; ++i) {
        double a = 2 * std::numbers::pi * i / count, r = 0.95 * std::sqrt((i + 0.5) / count);
        Vec3 target(r * std::cos(a), r * std::sin(a), 0);
        Vec3 origin(0, 0, 4);
        rays.push_back(Ray{origin, normalize(target - origin), 0, kInfinity});
    }
    return rays;
}

/// A unit sphere of material `m` at the origin under a uniform environment of radiance 1.
void furnace(Scene& scene, const Material& m) {
    scene.integrator = "path";
    scene.maxDepth = kMaxDepthLimit;
    scene.background = Background{Vec3(1), Vec3(1)};
    scene.primitives.addSphere(Sphere{{0, 0, 0}, 1, {}}, scene.addMaterial(m));
    scene.prepare();
}

void expectEverywhere(const Scene& scene, const Integrator& integrator, double expected, int n,
                      const char* what) {
    uint64_t seed = 1;
    for (const Ray& ray : raysAtTheSphere(24)) {
        test::MeanEstimate e = estimate(scene, integrator, ray, n, seed++);
        EXPECT_NEAR(e.mean(), expected, kZ * e.standardError() + 1e-9)
            << what << ": direction " << ray.dir.x << " " << ray.dir.y << " " << ray.dir.z
            << ", standard error " << e.standardError();
    }
}

/// A material of diffuse D, specular S and transmission T.
Material material(double d, double s, double t = 0) {
    Material m;
    m.diffuse = Vec3(d);
    m.specular = Vec3(s);
    m.transmission = Vec3(t);
    return m;
}

struct FurnaceCase {
    const char* what;
    Material m;
    double expected;  ///< Radiance everywhere on the sphere.
    int samples;      ///< Per direction.
};

TEST(PathFurnace, SpheresRenderTheirAnalyticRadiance) {
    const FurnaceCase cases[] = {
        {"Lambertian of albedo 1 is invisible", material(1, 0), 1, 400},
        // A convex object sees the environment over its whole hemisphere: one bounce gives
        // albedo x 1, and no light returns to it ("the rest" is 0).
        {"Lambertian of albedo 0.5 reflects half", material(0.5, 0), 0.5, 400},
        {"a perfect mirror is invisible", material(0, 1), 1, 16},
        // Every sample's weight is exactly 1 (reflect or refract by Fresnel, radiance scaled in
        // and out of the glass); paths still inside after kMaxDepthLimit events are lost: below
        // 0.1^30 of the light here.
        {"a smooth dielectric is invisible", material(0, 0, 1), 1, 64},
    };
    for (const FurnaceCase& c : cases) {
        Scene scene;
        furnace(scene, c.m);
        PathIntegrator integrator(scene);
        expectEverywhere(scene, integrator, c.expected, c.samples, c.what);
    }
}

TEST(PathFurnace, RoughConductorsOfReflectanceOneAreInvisible) {
    // GGX with Kulla-Conty's multiple-scattering compensation (render/bsdfs/bsdf.h) keeps the
    // energy single scattering loses; its albedo table is within 6.2e-4 of exact.
    for (double alpha : {0.1, 0.3, 0.6, 1.0}) {
        Scene scene;
        Material m = material(0, 1);
        m.roughness = alpha;
        furnace(scene, m);
        PathIntegrator integrator(scene);
        uint64_t seed = 1;
        for (const Ray& ray : raysAtTheSphere(12)) {
            test::MeanEstimate e = estimate(scene, integrator, ray, 2000, seed++);
            EXPECT_NEAR(e.mean(), 1, kZ * e.standardError() + 2 * 6.2e-4)
                << "alpha " << alpha << ", standard error " << e.standardError();
        }
    }
}

TEST(PathFurnace, AConstantEnvironmentMapIsAUniformEnvironment) {
    Scene scene;
    furnace(scene, material(1, 0));
    scene.environment = std::make_shared<EnvironmentMap>(4, 2, std::vector<float>(24, 0.5f), 2.0);
    PathIntegrator integrator(scene);
    expectEverywhere(scene, integrator, 1, 400, "Lambertian albedo 1 in a map of radiance 1");
}

TEST(PathFurnace, TheStrategiesAgreeUnderAnEnvironmentMap) {
    // A dim sky with a small bright sun in front of the sphere (towards +z, 50 degrees up):
    // light sampling finds the sun, BSDF sampling the sky.
    const int w = 64, h = 32;
    std::vector<float> rgb(w * h * 3, 0.2f);
    for (int y = 8; y < 10; ++y)
        for (int x = 47; x < 49; ++x)
            for (int c = 0; c < 3; ++c)
                rgb[(y * w + x) * 3 + c] = 400.0f * static_cast<float>(c + 1);
    Scene scene;
    furnace(scene, material(0.6, 0));
    scene.environment = std::make_shared<EnvironmentMap>(w, h, rgb, 1.0, 20.0);
    PathIntegrator mis(scene), lightsOnly(scene, PathIntegrator::Strategy::LightsOnly),
        bsdfOnly(scene, PathIntegrator::Strategy::BsdfOnly);
    uint64_t seed = 50;
    for (const Ray& ray : raysAtTheSphere(6)) {
        test::MeanEstimate a = estimate(scene, mis, ray, 20000, seed);
        test::MeanEstimate b = estimate(scene, lightsOnly, ray, 20000, seed + 1);
        test::MeanEstimate d = estimate(scene, bsdfOnly, ray, 20000, seed + 2);
        seed += 3;
        EXPECT_NEAR(a.mean(), b.mean(), kZ * std::hypot(a.standardError(), b.standardError()));
        EXPECT_NEAR(a.mean(), d.mean(), kZ * std::hypot(a.standardError(), d.standardError()));
        EXPECT_LT(a.standardError(), d.standardError()) << "MIS no better than BSDF sampling";
    }
}

TEST(PathFurnace, TheStrategiesAgreeOnAHalfWhiteSphere) {
    Scene scene;
    furnace(scene, material(0.5, 0));
    for (auto s : {PathIntegrator::Strategy::LightsOnly, PathIntegrator::Strategy::BsdfOnly}) {
        PathIntegrator integrator(scene, s);
        expectEverywhere(scene, integrator, 0.5, 400, "one strategy");
    }
}

TEST(PathClosedSphere, TheInsideOfAnEmittingDiffuseSphereIsEOverOneMinusRho) {
    // Every point inside sees the sphere's radiance L = E + rho L everywhere: L = E / (1 - rho).
    for (double rho : {0.3, 0.7}) {
        Scene scene;
        scene.integrator = "path";
        scene.maxDepth = kMaxDepthLimit;
        Material m;
        m.diffuse = Vec3(rho);
        m.emission = Vec3(0.25);
        scene.primitives.addSphere(Sphere{{0, 0, 0}, 2, {}}, scene.addMaterial(m));
        scene.prepare();
        PathIntegrator integrator(scene);
        const double expected = 0.25 / (1 - rho);
        const double truncation = 0.25 * std::pow(rho, kMaxDepthLimit + 1) / (1 - rho);
        uint64_t seed = 100;
        for (Vec3 dir : {Vec3(1, 0, 0), Vec3(0, -1, 0), normalize(Vec3(1, 2, -3))}) {
            Ray ray{{0.3, -0.5, 0.8}, dir, 0, kInfinity};
            test::MeanEstimate e = estimate(scene, integrator, ray, 4000, seed++);
            EXPECT_NEAR(e.mean(), expected, kZ * e.standardError() + truncation)
                << "rho " << rho << ", standard error " << e.standardError();
        }
    }
}

// Bounce limits by kind (Scene::bounces, --max-bounces) end paths as maxdepth does, each
// counting only its own kind of bounce.
TEST(PathBounceLimits, ADiffuseLimitEndsPathsInsideAnEmittingSphereAsMaxdepthDoes) {
    // Inside a closed emitting sphere every bounce is diffuse: after n of them the path has
    // gathered E (1 + rho + ... + rho^n), whichever of the two limits is n.
    // (Within 1e-3 of it: sampling the sphere's light from inside is 4e-4 off at n = 1, as it
    // is with maxdepth.) The two limits give the same paths, so the same estimate.
    const double rho = 0.7, emitted = 0.25;
    for (int n : {1, 3}) {
        double means[2];
        for (bool byKind : {true, false}) {
            Scene scene;
            scene.integrator = "path";
            scene.maxDepth = byKind ? kMaxDepthLimit : n;
            if (byKind) scene.bounces.diffuse = n;
            // Limits of the other kinds change nothing here.
            scene.bounces.glossy = scene.bounces.transmission = scene.bounces.volume = 1;
            Material m;
            m.diffuse = Vec3(rho);
            m.emission = Vec3(emitted);
            scene.primitives.addSphere(Sphere{{0, 0, 0}, 2, {}}, scene.addMaterial(m));
            scene.prepare();
            PathIntegrator integrator(scene);
            const double expected = emitted * (1 - std::pow(rho, n + 1)) / (1 - rho);
            Ray ray{{0.3, -0.5, 0.8}, normalize(Vec3(1, 2, -3)), 0, kInfinity};
            test::MeanEstimate e = estimate(scene, integrator, ray, 4000, 7);
            EXPECT_NEAR(e.mean(), expected, kZ * e.standardError() + 1e-3 * expected)
                << "n " << n << (byKind ? ", diffuse limit" : ", maxdepth") << ", standard error "
                << e.standardError();
            means[byKind] = e.mean();
        }
        EXPECT_EQ(means[0], means[1]) << "n " << n;
        // One more bounce gathers more: the limit is not ignored.
        EXPECT_GT(emitted * (1 - std::pow(rho, n + 2)) / (1 - rho) - means[1], 0.05);
    }
}

TEST(PathBounceLimits, ATransmissionLimitDarkensGlassAndNoOtherLimitDoes) {
    // A smooth glass sphere in a white furnace is invisible (radiance 1) when paths may go
    // through it; a path that enters and leaves refracts twice.
    auto glassWith = [](BounceLimits limits) {
        auto scene = std::make_unique<Scene>();
        furnace(*scene, material(0, 0, 1));
        scene->bounces = limits;
        return scene;
    };
    {
        auto scene = glassWith({.diffuse = 1, .volume = 1});
        expectEverywhere(*scene, PathIntegrator(*scene), 1, 64, "diffuse and volume limits 1");
    }
    {
        auto scene = glassWith({.transmission = 2});
        expectEverywhere(*scene, PathIntegrator(*scene), 1, 64, "transmission limit 2");
    }
    // With one transmission a path that enters ends inside: only the light the surface
    // reflects (Fresnel, well below a third at these angles) is left.
    auto scene = glassWith({.transmission = 1});
    PathIntegrator integrator(*scene);
    uint64_t seed = 1;
    for (const Ray& ray : raysAtTheSphere(8)) {
        test::MeanEstimate e = estimate(*scene, integrator, ray, 256, seed++);
        EXPECT_GT(e.mean(), 0.01) << ray.dir;
        EXPECT_LT(e.mean(), 0.33) << ray.dir;
    }
}

/// A room for the strategies: a floor, a rough glossy sphere and a diffuse one, lit by a quad
/// light, a small emissive sphere and a point light.
void lightsAndGloss(Scene& scene) {
    scene.integrator = "path";
    scene.maxDepth = 3;
    Material floor;
    floor.diffuse = Vec3(0.6, 0.5, 0.4);
    uint32_t f = scene.addMaterial(floor);
    scene.primitives.addTriangle({-5, 0, -5}, {5, 0, 5}, {5, 0, -5}, nullptr, f);
    scene.primitives.addTriangle({-5, 0, -5}, {-5, 0, 5}, {5, 0, 5}, nullptr, f);
    Material glossy;
    glossy.diffuse = Vec3(0.2);
    glossy.specular = Vec3(0.7);
    glossy.roughness = 0.2;
    scene.primitives.addSphere(Sphere{{-1, 1, 0}, 1, {}}, scene.addMaterial(glossy));
    Material diffuse;
    diffuse.diffuse = Vec3(0.8);
    scene.primitives.addSphere(Sphere{{1.2, 0.7, 0.5}, 0.7, {}}, scene.addMaterial(diffuse));
    Material lamp;
    lamp.emission = Vec3(8, 6, 4);
    scene.primitives.addSphere(Sphere{{1.5, 2.5, -1}, 0.3, {}}, scene.addMaterial(lamp));
    Material panel;
    panel.emission = Vec3(3);
    panel.frontEmissionOnly = true;
    uint32_t p = scene.addMaterial(panel);
    // Facing down: cross(b - a, c - a) points to -y.
    scene.primitives.addTriangle({-1, 3, -1}, {1, 3, 1}, {-1, 3, 1}, nullptr, p);
    scene.primitives.addTriangle({-1, 3, -1}, {1, 3, -1}, {1, 3, 1}, nullptr, p);
    LightSpec point;
    point.position = Vec3(-2, 2, 2);
    point.color = Vec3(2);
    scene.lights.push_back(point);
    scene.prepare();
}

// A closed room of separate wall quads that share their edges, grey walls lit by a white lamp
// inside, a green sky outside: no path may reach the sky. Each path's green equals its red
// unless it does, so the check is exact. Camera rays hit the floor within the spawn offset
// (0.001) of a wall, where rays that left along their direction started beyond the wall's plane
// and escaped through the corner (issue 22: thin lines of sky light along a room's corners).
TEST(PathCorners, NoPathLeavesAClosedRoomThroughItsCorners) {
    Scene scene;
    scene.integrator = "path";
    scene.maxDepth = 6;
    scene.background = Background{Vec3(0, 1, 0), Vec3(0, 1, 0)};
    Material wall;
    wall.diffuse = Vec3(0.7);
    const uint32_t w = scene.addMaterial(wall);
    const Vec3 c[8] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                       {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
    // Floor, ceiling, back, front, left and right: two triangles each, facing in.
    const int quads[6][4] = {{0, 1, 5, 4}, {3, 7, 6, 2}, {0, 3, 2, 1},
                             {4, 5, 6, 7}, {0, 4, 7, 3}, {1, 2, 6, 5}};
    for (const auto& q : quads) {
        scene.primitives.addTriangle(c[q[0]], c[q[1]], c[q[2]], nullptr, w);
        scene.primitives.addTriangle(c[q[0]], c[q[2]], c[q[3]], nullptr, w);
    }
    LightSpec lamp;
    lamp.position = Vec3(0.2, 0.6, -0.1);
    lamp.color = Vec3(1);
    scene.lights.push_back(lamp);
    scene.prepare();
    PathIntegrator integrator(scene);
    int samples = 0;
    double mostGreen = 0;
    for (double gap : {1e-4, 3e-4, 6e-4, 9e-4})
        for (double z : {-0.5, 0.0, 0.7}) {
            // From the room's middle at the floor, a hair from the left wall (x = -1).
            const Vec3 target(-1 + gap, -1, z);
            const Ray ray{Vec3(0.3, 0.2, 0.1), normalize(target - Vec3(0.3, 0.2, 0.1)), 0,
                          kInfinity};
            Hit hit;
            ASSERT_TRUE(scene.bvh().intersect(ray, hit));
            for (int i = 0; i < 2000; ++i) {
                RayCounts counts;
                PathContext ctx{Rng(77 + i), counts};
                // z * 10 + 10 >= 5: a negative double converted to an unsigned integer is
                // undefined (UBSan's float-cast-overflow).
                ctx.pixelSeed =
                    77 + static_cast<uint64_t>(gap * 1e5) + static_cast<uint64_t>(z * 10 + 10);
                ctx.sampleIndex = static_cast<uint32_t>(i);
                const Vec3 L = integrator.li(ray, &hit, ctx);
                mostGreen = std::max(mostGreen, L.y - L.x);
                ++samples;
            }
        }
    EXPECT_EQ(samples, 24000);
    EXPECT_EQ(mostGreen, 0) << "a path saw the sky outside the room";
}

// --clamp-indirect: each sample's light through two or more bounces is at most the clamp in
// its largest channel, light through fewer is untouched, and a clamp no sample reaches changes
// nothing. A path of the scene's 3 bounces adds at most 4 indirect terms (next-event estimation
// at its 2nd and 3rd vertex, emission found by its 3rd and 4th ray): over a direct-only render
// of the same random numbers, a clamped sample gains at most 4 clamps.
TEST(PathClampIndirect, ClampsLightAfterTwoBouncesOnly) {
    Scene scene;
    lightsAndGloss(scene);
    const Ray ray{Vec3(0, 1.5, 5), normalize(Vec3(0.2, 0, 2) - Vec3(0, 1.5, 5)), 0, kInfinity};
    Hit hit;
    ASSERT_TRUE(scene.bvh().intersect(ray, hit));
    auto sample = [&](int i) {
        PathIntegrator integrator(scene);
        RayCounts counts;
        PathContext ctx{Rng(5 + i), counts};
        ctx.pixelSeed = 11;
        ctx.sampleIndex = static_cast<uint32_t>(i);
        return integrator.li(ray, &hit, ctx);
    };
    constexpr double kClamp = 0.001;
    double clampedSum = 0, fullSum = 0;
    int changed = 0;
    for (int i = 0; i < 400; ++i) {
        scene.clampIndirect = 0;
        const Vec3 full = sample(i);
        scene.clampIndirect = 1e30;
        EXPECT_EQ(sample(i), full) << "a clamp no sample reaches changed sample " << i;
        scene.clampIndirect = kClamp;
        const Vec3 clamped = sample(i);
        scene.maxDepth = 1;
        const Vec3 direct = sample(i);
        scene.clampIndirect = 0;
        EXPECT_EQ(sample(i), direct) << "direct light was clamped in sample " << i;
        scene.maxDepth = 3;
        for (int c = 0; c < 3; ++c) {
            EXPECT_GE(clamped[c], direct[c] - 1e-12) << i;
            EXPECT_LE(clamped[c], direct[c] + 4 * kClamp + 1e-12) << i;
        }
        changed += !(clamped == full);
        clampedSum += clamped.x;
        fullSum += full.x;
    }
    // An open scene: most bounces off the floor leave it; those that meet a sphere bring
    // indirect light above the clamp (13 of the 400 samples).
    EXPECT_GT(changed, 5);
    EXPECT_LT(clampedSum, fullSum);
}

TEST(PathStrategies, LightBsdfAndMisEstimatesAgree) {
    Scene scene;
    lightsAndGloss(scene);
    PathIntegrator mis(scene), lightsOnly(scene, PathIntegrator::Strategy::LightsOnly),
        bsdfOnly(scene, PathIntegrator::Strategy::BsdfOnly);
    // Camera rays at the glossy sphere (the highlight of the panel included), the diffuse
    // one and the floor.
    const Vec3 eye(0, 1.5, 5);
    uint64_t seed = 7;
    int compared = 0;
    for (Vec3 target : {Vec3(-1, 1.2, 0.9), Vec3(-0.6, 1.6, 0.8), Vec3(1.2, 0.9, 1.1),
                        Vec3(0.2, 0, 2), Vec3(-2, 0, 1), Vec3(2, 0, -2)}) {
        Ray ray{eye, normalize(target - eye), 0, kInfinity};
        for (int c = 0; c < 3; ++c) {
            test::MeanEstimate a = estimate(scene, mis, ray, 20000, seed, c);
            test::MeanEstimate b = estimate(scene, lightsOnly, ray, 20000, seed + 1, c);
            test::MeanEstimate d = estimate(scene, bsdfOnly, ray, 20000, seed + 2, c);
            seed += 3;
            auto both = [](const test::MeanEstimate& x, const test::MeanEstimate& y) {
                return kZ * std::hypot(x.standardError(), y.standardError());
            };
            EXPECT_NEAR(a.mean(), b.mean(), both(a, b)) << "MIS vs lights only, channel " << c;
            EXPECT_NEAR(a.mean(), d.mean(), both(a, d)) << "MIS vs BSDF only, channel " << c;
            EXPECT_GT(a.mean(), 0);
            // MIS is never much worse than the better of the two.
            EXPECT_LT(a.standardError(),
                      1.5 * std::min(b.standardError(), d.standardError()) + 1e-12);
            ++compared;
        }
    }
    EXPECT_EQ(compared, 18);
}

TEST(PathIntegrator, IsChosenByNameAndIgnoresAmbient) {
    Scene scene;
    scene.integrator = "path";
    Material m;
    m.ambient = Vec3(0.5);  // the course's stand-in for indirect light: not used
    m.diffuse = Vec3(0.5);
    scene.primitives.addSphere(Sphere{{0, 0, 0}, 1, {}}, scene.addMaterial(m));
    scene.prepare();
    std::unique_ptr<Integrator> integrator = makeIntegrator(scene, {});
    ASSERT_NE(dynamic_cast<PathIntegrator*>(integrator.get()), nullptr);
    test::MeanEstimate e =
        estimate(scene, *integrator, Ray{{0, 0, 4}, {0, 0, -1}, 0, kInfinity}, 16, 3);
    EXPECT_EQ(e.mean(), 0) << "no light, no background: black";
}

}  // namespace
}  // namespace glint
