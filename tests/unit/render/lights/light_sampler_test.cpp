// The light sampler (render/lights/light_sampler.h): its densities against geometry. For a light of
// any shape, the mean of 1 / pdf over its samples from a point is the solid angle it covers
// there, counted once per surface a direction crosses (twice for a closed shape, whose far
// side is sampled too); the solid angle is measured independently by casting uniformly
// distributed rays. And pdfHit(), which the path tracer uses when a ray finds a light, gives
// the same density as sample() for the same point.

#include "glint/render/lights/light_sampler.h"

#include <gtest/gtest.h>

#include <numbers>

#include "glint/core/spawn.h"
#include "glint/math/rng.h"
#include "unit/statistics.h"

namespace glint {
namespace {

constexpr double kZ = 5;  // as in path_test.cpp

Material emitter() {
    Material m;
    m.emission = Vec3(1, 2, 3);
    return m;
}

Transform placed(const Mat4& objectFromCanonical) {
    // Stretched, turned and moved, so that the density's correction for the transform counts.
    Mat4 world = Mat4::translate(0.3, -0.2, 0.1) * Mat4::rotate(1, 2, 0.5, 35) *
                 Mat4::scale(1.3, 0.6, 0.9) * objectFromCanonical;
    return *Transform::fromMatrix(world);
}

/// Checks the sampler of the one light in `scene` from point `p`; `surfaces`: how many
/// surfaces of the light a ray through it crosses (2 for closed shapes, 1 for flat ones).
void checkLight(const Scene& scene, const Vec3& p, int surfaces, const char* what) {
    LightSampler lights(scene);
    ASSERT_EQ(lights.size(), 1u) << what;
    Rng rng(42);
    // Per octant of directions from p, so that a density wrong in one part of the light
    // cannot hide behind one right on average.
    auto octant = [](const Vec3& d) { return (d.x > 0) + 2 * (d.y > 0) + 4 * (d.z > 0); };
    test::MeanEstimate inversePdf[8], hits[8];
    const int n = 200000;
    int consistent = 0, inconsistent = 0;
    for (int i = 0; i < n; ++i) {
        Point2 u{rng.uniform(), rng.uniform()};
        std::optional<LightSample> s = lights.sample(p, Vec3(0), rng.uniform(), u);
        int o = s ? octant(s->wi) : -1;
        for (int k = 0; k < 8; ++k) inversePdf[k].add(k == o ? 1 / s->pdf : 0.0);
        if (s) {
            EXPECT_EQ(s->L, Vec3(1, 2, 3)) << what;
            EXPECT_FALSE(s->delta);
            // The first surface the ray towards the sample meets, if it is the sampled point,
            // must have the same density by pdfHit().
            Ray ray{p, s->wi, 0, kInfinity};
            Hit hit;
            if (scene.bvh().intersect(ray, hit) && std::abs(hit.t - s->distance) < 1e-4) {
                SurfaceInteraction si = scene.primitives.interaction(ray, hit);
                // Points within rounding of an edge may be given the neighbouring face's
                // normal by the hit, and grazing ones lose digits: a few may differ.
                (std::abs(lights.pdfHit(p, Vec3(0), ray.dir, hit, si) - s->pdf) <= 1e-6 * s->pdf
                     ? consistent
                     : inconsistent)++;
            }
        }
        // Independently: the solid angle, by uniformly distributed rays.
        Ray ray{p, sampleUniformSphere({rng.uniform(), rng.uniform()}), 0, kInfinity};
        Hit hit;
        bool found = scene.bvh().intersect(ray, hit);
        for (int k = 0; k < 8; ++k)
            hits[k].add(found && k == octant(ray.dir) ? 4 * std::numbers::pi : 0.0);
    }
    EXPECT_GT(consistent, n / 10) << what;
    EXPECT_LE(inconsistent, consistent / 1000) << what;
    for (int k = 0; k < 8; ++k) {
        double bound =
            kZ * std::hypot(inversePdf[k].standardError(), surfaces * hits[k].standardError());
        EXPECT_NEAR(inversePdf[k].mean(), surfaces * hits[k].mean(), bound)
            << what << ", octant " << k << ": E[1/pdf] " << inversePdf[k].mean() << ", solid angle "
            << hits[k].mean();
    }
}

TEST(LightSampler, TrianglesCoverTheirSolidAngle) {
    Scene scene;
    scene.primitives.addTriangle({-1, 0, -1}, {1, 0.5, -1}, {0, 1, 1}, nullptr,
                                 scene.addMaterial(emitter()));
    scene.prepare();
    checkLight(scene, {0.2, 0.6, 0.3}, 1, "triangle");
}

TEST(LightSampler, TrianglesThatAnInstancePlacesAreLightsToo) {
    // A shared mesh of one emissive triangle (and a plain one), placed once, turned and moved:
    // the placed triangle is sampled, and a ray that meets it gets the same density.
    Scene scene;
    const uint32_t glow = scene.addMaterial(emitter());
    Primitives mesh;
    mesh.addTriangle({-1, 0, -1}, {1, 0.5, -1}, {0, 1, 1}, nullptr, glow);
    mesh.addTriangle({3, 0, 0}, {4, 0, 0}, {3, 1, 0}, nullptr, scene.addMaterial(Material{}));
    const uint32_t index = scene.addSharedMesh(std::move(mesh));
    scene.primitives.addInstance(
        index, *Transform::fromMatrix(Mat4::translate(0.2, -0.1, 0.3) * Mat4::rotate(0, 1, 0, 30)));
    scene.prepare();
    checkLight(scene, {0.3, 0.7, 0.4}, 1, "instanced triangle");
}

TEST(LightSampler, TransformedSpheresCoverTheirSolidAngleTwice) {
    Scene scene;
    scene.primitives.addSphere(Sphere{{0.2, 0, 0}, 0.8, placed(Mat4())},
                               scene.addMaterial(emitter()));
    scene.prepare();
    checkLight(scene, {1.2, 0.8, 0.6}, 2, "ellipsoid");
}

TEST(LightSampler, RoundSpheresAreSampledByTheirConeCoveringTheirSolidAngleOnce) {
    // Turned, scaled alike on every axis and moved: a round sphere, sampled over the cone of
    // directions it fills, so every sample is on the side facing the point. Near (a cone of
    // 37 degrees) and far (under 1.5 degrees, where the cone's cosine comes from its sine).
    for (double distance : {1.0, 40.0}) {
        Scene scene;
        const Mat4 similar = Mat4::translate(0.3, -0.2, 0.1) * Mat4::rotate(1, 2, 0.5, 35) *
                             Mat4::scale(0.7, 0.7, 0.7);
        scene.primitives.addSphere(Sphere{{0.2, 0, 0}, 0.8, *Transform::fromMatrix(similar)},
                                   scene.addMaterial(emitter()));
        scene.prepare();
        const Vec3 center = Transform::fromMatrix(similar)->point({0.2, 0, 0});
        checkLight(scene, center + normalize(Vec3(1, 0.7, 0.5)) * distance, 1,
                   distance < 2 ? "round sphere, near" : "round sphere, far");
    }
}

TEST(LightSampler, EmissivePlanesCoverTheHalfOfTheDirectionsThatMeetThem) {
    // Tilted, below the point: sampled by the cosine about its normal, over the directions
    // that meet it (E[1 / pdf] is their solid angle, 2 pi, in each octant its share).
    Scene scene;
    const std::optional<Plane> plane =
        Plane::make({0, -0.5, 0}, {0.2, 1, -0.3}, *Transform::fromMatrix(Mat4()));
    ASSERT_TRUE(plane);
    scene.primitives.addPlane(*plane, scene.addMaterial(emitter()));
    scene.prepare();
    checkLight(scene, {0.3, 0.4, -0.2}, 1, "plane");
}

TEST(LightSampler, TransformedShapesCoverTheirSolidAngle) {
    double k = 0;
    struct Case {
        ShapeKind kind;
        Mat4 placement;
        double k;
        int surfaces;
        const char* what;
    } cases[] = {
        {ShapeKind::Box, boxPlacement({-0.5, -0.4, -0.3}, {0.5, 0.4, 0.6}), 1, 2, "box"},
        {ShapeKind::Cylinder, cylinderPlacement({0, -0.5, 0}, {0, 0.5, 0.2}, 0.4), 1, 2,
         "cylinder"},
        {ShapeKind::Cone, conePlacement({0, -0.5, 0}, 0.6, {0, 0.5, 0}, 0.2, k), 0, 2, "cone"},
        {ShapeKind::Cone, conePlacement({0, -0.5, 0}, 0.6, {0.1, 0.5, 0}, 0, k), 0, 2,
         "pointed cone"},
        {ShapeKind::Disk, diskPlacement({0, 0, 0}, {0.3, 1, 0.2}, 0.7), 1, 1, "disk"},
    };
    conePlacement({0, -0.5, 0}, 0.6, {0, 0.5, 0}, 0.2, cases[2].k);
    conePlacement({0, -0.5, 0}, 0.6, {0.1, 0.5, 0}, 0, cases[3].k);
    for (const Case& c : cases) {
        Scene scene;
        scene.primitives.addShape(Shape{c.kind, c.k, placed(c.placement)},
                                  scene.addMaterial(emitter()));
        scene.prepare();
        checkLight(scene, {0.9, 0.5, 0.7}, c.surfaces, c.what);
    }
}

TEST(LightSampler, QuadLightsEmitFromTheirFrontOnly) {
    Scene scene;
    Material m = emitter();
    m.frontEmissionOnly = true;
    uint32_t id = scene.addMaterial(m);
    // Facing +y: cross(b - a, c - a) = (0, 4, 0).
    scene.primitives.addTriangle({-1, 1, -1}, {-1, 1, 1}, {1, 1, 1}, nullptr, id);
    scene.prepare();
    LightSampler lights(scene);
    Rng rng(3);
    int above = 0;
    for (int i = 0; i < 1000; ++i) {
        Point2 u{rng.uniform(), rng.uniform()};
        EXPECT_FALSE(lights.sample({0, 0, 0}, Vec3(0), 0.5, u)) << "sampled from behind";
        above += lights.sample({0, 2, 0}, Vec3(0), 0.5, u).has_value();
    }
    EXPECT_EQ(above, 1000);
}

TEST(LightSampler, LightsAreChosenAsTheirProbabilitiesSay) {
    // Two lamps of equal area, one three times as bright; a sun and a sky at infinity.
    Scene scene;
    Material dim = emitter(), bright = emitter();
    bright.emission = Vec3(3, 6, 9);
    scene.primitives.addTriangle({-1, 0, 0}, {0, 0, 0}, {-1, 1, 0}, nullptr,
                                 scene.addMaterial(dim));
    scene.primitives.addTriangle({1, 0, 0}, {2, 0, 0}, {1, 1, 0}, nullptr,
                                 scene.addMaterial(bright));
    LightSpec sun;
    sun.kind = LightSpec::Kind::Directional;
    sun.direction = normalize(Vec3(1, 1, 1));
    sun.color = Vec3(2);
    scene.lights.push_back(sun);
    scene.background = Background{Vec3(0.1), Vec3(0.3)};
    scene.prepare();
    LightSampler lights(scene);
    ASSERT_EQ(lights.size(), 4u);
    const Vec3 p(0.5, 0.5, 3), n(0, 0, 1);
    double total = 0;
    for (size_t k = 0; k < lights.size(); ++k) total += lights.choiceProbability(k, p, n);
    EXPECT_NEAR(total, 1, 1e-12);
    // Indices: the sun (delta lights first), the dim and the bright lamp, the sky.
    Rng rng(5);
    int counts[4] = {0, 0, 0, 0};
    const int trials = 60000;
    for (int i = 0; i < trials; ++i) {
        std::optional<LightSample> s =
            lights.sample(p, n, rng.uniform(), {rng.uniform(), rng.uniform()});
        ASSERT_TRUE(s);
        const int k = s->delta ? 0 : std::isinf(s->distance) ? 3 : s->L.x == 3 ? 2 : 1;
        counts[k]++;
    }
    for (int k = 0; k < 4; ++k) {
        const double q = lights.choiceProbability(static_cast<size_t>(k), p, n);
        EXPECT_NEAR(counts[k] / double(trials), q, 5 * std::sqrt(q * (1 - q) / trials)) << k;
    }
    // The bright lamp, three times the power, is the likelier; the sun (irradiance 2 pi)
    // outweighs the dim sky (pi^2 0.2).
    EXPECT_GT(lights.choiceProbability(2, p, n), lights.choiceProbability(1, p, n));
    EXPECT_GT(lights.choiceProbability(0, p, n), lights.choiceProbability(3, p, n));
}

TEST(LightSampler, TheBackgroundIsALightUnlessBlack) {
    Scene black;
    black.prepare();
    EXPECT_TRUE(LightSampler(black).empty());
    EXPECT_EQ(LightSampler(black).pdfEnvironment({0, 1, 0}, Vec3(0), Vec3(0)), 0);
    Scene sky;
    sky.background = Background{Vec3(0.1), Vec3(0.5, 0.7, 1)};
    sky.prepare();
    LightSampler lights(sky);
    ASSERT_EQ(lights.size(), 1u);
    EXPECT_DOUBLE_EQ(lights.pdfEnvironment({0, 1, 0}, Vec3(0), Vec3(0)),
                     1 / (4 * std::numbers::pi));
    std::optional<LightSample> s = lights.sample({0, 0, 0}, Vec3(0), 0.3, {0.2, 0.7});
    ASSERT_TRUE(s);
    EXPECT_EQ(s->L, sky.background.eval(s->wi));
    EXPECT_TRUE(std::isinf(s->distance));
}

}  // namespace
}  // namespace glint
