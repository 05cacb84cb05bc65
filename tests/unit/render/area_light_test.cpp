// Area lights: the jittered-grid estimate of irradiance converges to the analytic value.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "glint/math/rng.h"
#include "glint/scene/light.h"

namespace glint {
namespace {

/// Irradiance at `p` (normal `n`) from a polygon of uniform unit radiance lying wholly above
/// the tangent plane at `p`: Lambert's formula, E = 1/2 sum_i angle_i (n . unit normal of
/// the plane through p and edge i).
double polygonIrradiance(const std::vector<Vec3>& poly, const Vec3& p, const Vec3& n) {
    double sum = 0;
    for (size_t i = 0; i < poly.size(); ++i) {
        Vec3 a = normalize(poly[i] - p), b = normalize(poly[(i + 1) % poly.size()] - p);
        double angle = std::acos(std::clamp(dot(a, b), -1.0, 1.0));
        sum += angle * dot(n, normalize(cross(a, b)));
    }
    return std::abs(sum) / 2;
}

Light quad(const Vec3& corner, const Vec3& e1, const Vec3& e2) {
    Light l;
    l.kind = Light::Kind::Quad;
    l.position = corner;
    l.edge1 = e1;
    l.edge2 = e2;
    l.color = Vec3(1);
    return l;
}

/// One estimate of the irradiance with an n x n jittered grid, as the integrator takes it.
double estimate(const Light& l, const Vec3& p, const Vec3& n, int grid, Rng& rng) {
    double sum = 0;
    for (int j = 0; j < grid; ++j)
        for (int i = 0; i < grid; ++i) {
            double s = (i + static_cast<double>(rng.uniform())) / grid;
            double t = (j + static_cast<double>(rng.uniform())) / grid;
            LightSample ls = l.sampleQuad(p, s, t);
            sum += ls.radiance.x * std::max(0.0, dot(n, ls.wi));
        }
    return sum / (grid * grid);
}

struct Case {
    const char* name;
    Vec3 corner, e1, e2, p, n;
};

class QuadIrradiance : public testing::TestWithParam<Case> {};

TEST_P(QuadIrradiance, MeanOfEstimatesIsWithinFourStandardErrorsOfTheAnalyticValue) {
    const Case& c = GetParam();
    Light l = quad(c.corner, c.e1, c.e2);
    double exact = polygonIrradiance(
        {c.corner, c.corner + c.e1, c.corner + c.e1 + c.e2, c.corner + c.e2}, c.p, normalize(c.n));
    ASSERT_GT(exact, 0);
    Rng rng(2024);
    const int runs = 2000;
    for (int grid : {1, 4}) {
        double sum = 0, sum2 = 0;
        for (int r = 0; r < runs; ++r) {
            double e = estimate(l, c.p, normalize(c.n), grid, rng);
            sum += e;
            sum2 += e * e;
        }
        double mean = sum / runs;
        double se = std::sqrt(std::max(0.0, sum2 / runs - mean * mean) / runs);
        std::printf(
            "%s, %dx%d grid: exact %.6f, mean of %d estimates %.6f, error %+.2e (%.2f "
            "standard errors of %.2e)\n",
            c.name, grid, grid, exact, runs, mean, mean - exact, (mean - exact) / se, se);
        EXPECT_NEAR(mean, exact, 4 * se + 1e-12)
            << c.name << ", grid " << grid << ": exact " << exact << ", standard error " << se;
        // The 4 x 4 grid's estimates are usable ones (the 1 x 1 grid of a large, close light
        // is noisy by nature).
        if (grid == 4) {
            EXPECT_LT(se, 0.02 * exact) << c.name;
        }
    }
}

INSTANTIATE_TEST_SUITE_P(
    Area, QuadIrradiance,
    testing::Values(
        // A 1 x 1 light 1 above the point, facing down, centred.
        Case{"centred", {-0.5, 1, -0.5}, {1, 0, 0}, {0, 0, 1}, {0, 0, 0}, {0, 1, 0}},
        // Off to the side, tilted receiver.
        Case{"offset", {0.5, 2, -1}, {1.5, 0, 0}, {0, 0, 2}, {0, 0, 0}, {0.3, 1, 0.1}},
        // A sheared parallelogram, close and large.
        Case{"sheared", {-2, 0.5, -1}, {3, 0.2, 0.8}, {0, 0, 2}, {0, 0, 0}, {0, 1, 0}}),
    [](const testing::TestParamInfo<Case>& p) { return std::string(p.param.name); });

TEST(QuadLight, NothingFromBehindTheEmittingFace) {
    // cross((1, 0, 0), (0, 0, 1)) = (0, -1, 0): the light faces down; a point above sees its back.
    Light l = quad({-0.5, 0, -0.5}, {1, 0, 0}, {0, 0, 1});
    ASSERT_NEAR(l.quadNormal().y, -1, 1e-12);
    EXPECT_EQ(l.sampleQuad({0, 1, 0}, 0.5, 0.5).radiance, Vec3(0));
    EXPECT_GT(l.sampleQuad({0, -1, 0}, 0.5, 0.5).radiance.x, 0);
}

TEST(QuadLight, SampleRadianceIsRadianceTimesAreaTimesCosineOverDistanceSquared) {
    Light l = quad({-1, 2, -1}, {2, 0, 0}, {0, 0, 2});  // area 4, facing -y
    l.color = {2, 1, 0.5};
    LightSample ls = l.sampleQuad({0, 0, 0}, 0.5, 0.5);  // the centre, straight above
    EXPECT_NEAR(ls.distance, 2, 1e-12);
    EXPECT_NEAR(ls.wi.y, 1, 1e-12);
    EXPECT_NEAR(ls.radiance.x, 2 * 4 * 1 / 4.0, 1e-12);
    EXPECT_NEAR(ls.radiance.z, 0.5 * 4 * 1 / 4.0, 1e-12);
}

}  // namespace
}  // namespace glint
