// The scene's own lights (point, directional, quad): what sampleLi() draws and pdfLi() says; a
// quad's irradiance estimated with sampleLi() converges to the analytic value.

#include "glint/render/lights/light.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "glint/math/rng.h"
#include "unit/scene/quad_light_support.h"
#include "unit/statistics.h"
#include "unit/test_support.h"

namespace glint {
namespace {

using test::expectNear;

/// The quad light of unit radiance (test::quadLight) that the Whitted integrator samples.
QuadLight quadLight(const Vec3& corner, const Vec3& e1, const Vec3& e2) {
    return *lightFromSpec(test::quadLight(corner, e1, e2)).as<QuadLight>();
}

TEST(PointLight, SampleLiIsTheAttenuatedColourFromItsDirectionWithPdfOne) {
    PointLight l{{0, 4, 3}, {10, 20, 30}, {1, 0.5, 0.25}};
    EXPECT_TRUE(l.isDelta());
    std::optional<LightLiSample> s = l.sampleLi({0, 0, 0}, {0.3, 0.9});
    ASSERT_TRUE(s);
    expectNear(s->wi, {0, 0.8, 0.6});
    EXPECT_DOUBLE_EQ(s->distance, 5);
    expectNear(s->L, Vec3(10, 20, 30) / (1 + 0.5 * 5 + 0.25 * 25));
    EXPECT_EQ(s->invPdf, 1);
    EXPECT_EQ(s->pdf, 1);
    EXPECT_TRUE(s->delta);
    // No BSDF sample can hit a point.
    EXPECT_EQ(l.pdfLi({0, 0, 0}, {l.position, Vec3(0), s->wi}), 0);
    // At the light itself there is no direction.
    EXPECT_FALSE(l.sampleLi(l.position, {}));
}

TEST(DirectionalLight, SampleLiIsItsColourFromItsDirectionAtInfiniteDistance) {
    DirectionalLight l{normalize(Vec3(1, 1, 0)), {0.5, 0.6, 0.7}};
    EXPECT_TRUE(l.isDelta());
    std::optional<LightLiSample> s = l.sampleLi({3, -2, 1}, {0.5, 0.5});
    ASSERT_TRUE(s);
    EXPECT_EQ(s->wi, l.direction);
    EXPECT_EQ(s->L, l.color);
    EXPECT_EQ(s->distance, kInfinity);
    EXPECT_EQ(s->pdf, 1);
    EXPECT_EQ(l.pdfLi({3, -2, 1}, {Vec3(0), Vec3(0), l.direction}), 0);
}

TEST(QuadLight, NothingFromBehindTheEmittingFace) {
    // cross((1, 0, 0), (0, 0, 1)) = (0, -1, 0): the light faces down; a point above sees its back.
    QuadLight l = quadLight({-0.5, 0, -0.5}, {1, 0, 0}, {0, 0, 1});
    ASSERT_NEAR(normalize(cross(l.edge1, l.edge2)).y, -1, 1e-12);
    EXPECT_FALSE(l.isDelta());
    EXPECT_FALSE(l.sampleLi({0, 1, 0}, {0.5, 0.5}));
    EXPECT_EQ(l.pdfLi({0, 1, 0}, {Vec3(0), Vec3(0), {0, -1, 0}}), 0);
    EXPECT_FALSE(l.sampleLi({3, 0, 0}, {0.5, 0.5}));  // in its plane
    ASSERT_TRUE(l.sampleLi({0, -1, 0}, {0.5, 0.5}));
    EXPECT_GT(l.pdfLi({0, -1, 0}, {Vec3(0), Vec3(0), {0, 1, 0}}), 0);
}

TEST(QuadLight, SampleLiIsUniformOverTheAreaConvertedToSolidAngle) {
    QuadLight l = quadLight({-1, 2, -1}, {2, 0, 0}, {0, 0, 2});  // area 4, facing -y
    l.color = {2, 1, 0.5};
    std::optional<LightLiSample> s = l.sampleLi({0, 0, 0}, {0.5, 0.5});  // the centre, above
    ASSERT_TRUE(s);
    EXPECT_NEAR(s->distance, 2, 1e-12);
    expectNear(s->wi, {0, 1, 0});
    EXPECT_EQ(s->L, l.color);  // the emitted radiance
    // 1 / pdf = A cos(theta_light) / r^2 = 4 * 1 / 4.
    EXPECT_NEAR(s->invPdf, 1, 1e-12);
    // A corner: r^2 = 6, cos(theta_light) = 2 / sqrt(6).
    s = l.sampleLi({0, 0, 0}, {1, 1});
    ASSERT_TRUE(s);
    expectNear(s->wi, Vec3(1, 2, 1) / std::sqrt(6.0));
    EXPECT_NEAR(s->pdf, 6 / (4 * 2 / std::sqrt(6.0)), 1e-12);
}

TEST(QuadLight, PdfLiIsThePdfSampleLiReturnedAndZeroOffTheQuad) {
    QuadLight l = quadLight({-2, 0.5, -1}, {3, 0.2, 0.8}, {0, 0, 2});  // sheared, facing down
    auto along = [](const Vec3& wi) { return LightPoint{Vec3(0), Vec3(0), wi}; };
    Rng rng(99);
    for (int k = 0; k < 2000; ++k) {
        Vec3 p(8 * rng.uniform() - 4, -3 * rng.uniform(), 8 * rng.uniform() - 4);
        std::optional<LightLiSample> s = l.sampleLi(p, {rng.uniform(), rng.uniform()});
        if (!s) continue;
        EXPECT_NEAR(l.pdfLi(p, along(s->wi)), s->pdf, 1e-9 * s->pdf) << k;
        // Just beyond an edge (s = 1.01): no density.
        Vec3 beyond = l.position + l.edge1 * 1.01 + l.edge2 * double(rng.uniform()) - p;
        EXPECT_EQ(l.pdfLi(p, along(normalize(beyond))), 0);
        EXPECT_EQ(l.pdfLi(p, along(-s->wi)), 0);  // away from the light
    }
}

TEST(QuadLight, PdfLiIntegratesToOneOverTheSphere) {
    // By uniform directions, independently of sampleLi: the mean of 4 pi pdfLi is 1.
    QuadLight l = quadLight({-0.5, 1, -0.5}, {1, 0, 0}, {0, 0, 1});
    Rng rng(5);
    test::MeanEstimate e;
    for (int k = 0; k < 1'000'000; ++k) {
        double z = 2 * rng.uniform() - 1, phi = 2 * std::numbers::pi * rng.uniform();
        double r = std::sqrt(std::max(0.0, 1 - z * z));
        const Vec3 wi(r * std::cos(phi), z, r * std::sin(phi));
        e.add(4 * std::numbers::pi * l.pdfLi({0, 0, 0}, {Vec3(0), Vec3(0), wi}));
    }
    EXPECT_NEAR(e.mean(), 1, 4 * e.standardError()) << "standard error " << e.standardError();
}

struct Case {
    const char* name;
    Vec3 corner, e1, e2, p, n;
};

class QuadIrradiance : public testing::TestWithParam<Case> {};

TEST_P(QuadIrradiance, SampleLiEstimateIsWithinFourStandardErrorsOfTheAnalyticValue) {
    const Case& c = GetParam();
    QuadLight l = quadLight(c.corner, c.e1, c.e2);
    Vec3 n = normalize(c.n);
    double exact = test::quadIrradiance(test::quadLight(c.corner, c.e1, c.e2), c.p, n);
    ASSERT_GT(exact, 0);
    Rng rng(2024);
    test::MeanEstimate e;
    for (int k = 0; k < 400000; ++k) {
        std::optional<LightLiSample> s = l.sampleLi(c.p, {rng.uniform(), rng.uniform()});
        e.add(s ? s->L.x * s->invPdf * std::max(0.0, dot(n, s->wi)) : 0);
    }
    std::printf("%s: exact %.6f, estimate %.6f, %+.2f standard errors of %.2e\n", c.name, exact,
                e.mean(), (e.mean() - exact) / e.standardError(), e.standardError());
    EXPECT_NEAR(e.mean(), exact, 4 * e.standardError()) << c.name;
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

}  // namespace
}  // namespace glint
