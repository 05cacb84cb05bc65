// The studio environment (scene/studio_environment.h): finite, non-negative and grey
// everywhere, the map holding the radiance it describes, and light of the strength a glTF
// viewer's studio gives: a white Lambertian surface facing up reflects about 1, one facing the
// camera somewhat less, the underside least, and the key light comes from above left in front.

#include "glint/scene/studio_environment.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "glint/math/rng.h"
#include "glint/render/integrators/path.h"
#include "unit/statistics.h"

namespace glint {
namespace {

constexpr double kPi = std::numbers::pi;

Vec3 sphericalDirection(double theta, double phi) {
    return {std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi)};
}

/// The irradiance of a surface of unit normal `n` from radiance(direction), by the midpoint
/// rule on a (theta, phi) grid fine enough for the softboxes' edges.
template <typename Radiance>
double irradiance(const Vec3& n, Radiance radiance) {
    const int rows = 512, columns = 1024;
    double sum = 0;
    for (int i = 0; i < rows; ++i) {
        double theta = kPi * (i + 0.5) / rows;
        double rowWeight = std::sin(theta) * (kPi / rows) * (2 * kPi / columns);
        for (int j = 0; j < columns; ++j) {
            Vec3 d = sphericalDirection(theta, 2 * kPi * (j + 0.5) / columns - kPi);
            double c = dot(n, d);
            if (c > 0) sum += radiance(d) * c * rowWeight;
        }
    }
    return sum;
}

TEST(StudioEnvironment, IsFiniteNonNegativeAndGreyEverywhere) {
    std::shared_ptr<const EnvironmentMap> map = studioEnvironment();
    ASSERT_TRUE(map);
    EXPECT_EQ(map->width(), kStudioWidth);
    EXPECT_EQ(map->height(), kStudioHeight);
    double lowest = 1e300, highest = 0;
    for (int y = 0; y < map->height(); ++y)
        for (int x = 0; x < map->width(); ++x) {
            Vec3 t = map->texel(x, y);
            ASSERT_TRUE(std::isfinite(t.x) && t.x >= 0) << x << "," << y;
            EXPECT_EQ(t.x, t.y);
            EXPECT_EQ(t.y, t.z);
            lowest = std::min(lowest, t.x);
            highest = std::max(highest, t.x);
        }
    // No direction is black (the dome lights every side) and the softboxes stand out.
    EXPECT_GT(lowest, 0.1);
    EXPECT_GT(highest, 10 * lowest);
    Rng rng(7);
    for (int i = 0; i < 10000; ++i) {
        double u = static_cast<double>(rng.uniform()), v = static_cast<double>(rng.uniform());
        Vec3 d = sphericalDirection(std::acos(1 - 2 * u), 2 * kPi * v);
        Vec3 L = map->eval(d);
        EXPECT_TRUE(std::isfinite(L.x) && L.x > 0 && L.x == L.z);
    }
}

TEST(StudioEnvironment, TheMapHoldsTheRadianceAtItsTexelCentresAndIsBuiltOnce) {
    std::shared_ptr<const EnvironmentMap> map = studioEnvironment();
    for (int y = 0; y < map->height(); y += 7)
        for (int x = 0; x < map->width(); x += 5) {
            Vec3 d = map->direction({(x + 0.5) / map->width(), (y + 0.5) / map->height()});
            EXPECT_NEAR(map->texel(x, y).x, studioRadiance(d).x, 1e-6 * studioRadiance(d).x);
        }
    EXPECT_EQ(studioEnvironment().get(), map.get());
}

TEST(StudioEnvironment, LightsWhiteSurfacesAsAViewersStudioDoes) {
    auto L = [](const Vec3& d) { return studioRadiance(d).x; };
    // White Lambertian surfaces reflect E / pi: about 1 facing up (a base colour shows as
    // itself through PBR Neutral), less facing the camera, least facing down; the key light is
    // on the left.
    double up = irradiance({0, 1, 0}, L) / kPi, front = irradiance({0, 0, 1}, L) / kPi,
           down = irradiance({0, -1, 0}, L) / kPi, left = irradiance({-1, 0, 0}, L) / kPi,
           right = irradiance({1, 0, 0}, L) / kPi, back = irradiance({0, 0, -1}, L) / kPi;
    EXPECT_GT(up, 0.8);
    EXPECT_LT(up, 1.3);
    EXPECT_GT(front, 0.4);
    EXPECT_LT(front, up);
    EXPECT_GT(down, 0.2);
    EXPECT_LT(down, 0.6);
    EXPECT_GT(left, right);
    EXPECT_GT(front, back);
    // The map's own irradiance agrees with the radiance it was made from.
    std::shared_ptr<const EnvironmentMap> map = studioEnvironment();
    double upMap = irradiance({0, 1, 0}, [&](const Vec3& d) { return map->eval(d).x; }) / kPi;
    EXPECT_NEAR(upMap, up, 0.01 * up);
}

TEST(StudioEnvironment, TheKeyLightIsAboveLeftInFront) {
    Vec3 brightest;
    double most = 0;
    for (int i = 1; i < 90; ++i)
        for (int j = 0; j < 180; ++j) {
            Vec3 d = sphericalDirection(kPi * i / 90, 2 * kPi * j / 180);
            if (double L = studioRadiance(d).x; L > most) {
                most = L;
                brightest = d;
            }
        }
    EXPECT_LT(brightest.x, 0);
    EXPECT_GT(brightest.y, 0.3);
    EXPECT_GT(brightest.z, 0);
}

TEST(StudioEnvironment, AWhiteDiffuseSphereRendersItsIrradianceOverPi) {
    // The path tracer in the studio: a white Lambertian sphere alone reflects E(n) / pi at each
    // point of normal n, E from the map by quadrature.
    Scene scene;
    scene.integrator = "path";
    scene.maxDepth = 4;
    scene.environment = studioEnvironment();
    Material white;
    white.diffuse = Vec3(1);
    scene.primitives.addSphere(Sphere{{0, 0, 0}, 1, {}}, scene.addMaterial(white));
    scene.prepare();
    PathIntegrator integrator(scene);
    const EnvironmentMap& map = *scene.environment;
    uint64_t seed = 11;
    for (Vec3 target : {Vec3(0, 0.8, 0.5), Vec3(0, 0, 1), Vec3(-0.6, 0.3, 0.7),
                        Vec3(0.6, -0.3, 0.7), Vec3(0, -0.9, 0.4)}) {
        Vec3 n = normalize(target);
        Ray ray{n * 4.0, -n, 0, kInfinity};  // straight at the point of normal n
        Hit hit;
        ASSERT_TRUE(scene.bvh().intersect(ray, hit));
        test::MeanEstimate e;
        for (int i = 0; i < 4000; ++i) {
            RayCounts counts;
            PathContext ctx{Rng(seed + i), counts};
            ctx.pixelSeed = seed;
            ctx.sampleIndex = static_cast<uint32_t>(i);
            e.add(integrator.li(ray, &hit, ctx).y);
        }
        seed += 4000;
        double expected = irradiance(n, [&](const Vec3& d) { return map.eval(d).y; }) / kPi;
        EXPECT_NEAR(e.mean(), expected, 5 * e.standardError() + 0.005 * expected)
            << "normal " << n.x << " " << n.y << " " << n.z;
    }
}

}  // namespace
}  // namespace glint
