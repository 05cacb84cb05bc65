#include "glint/render/bsdfs/optics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "glint/math/rng.h"

namespace glint {
namespace {

constexpr double kPi = std::numbers::pi;

TEST(Refract, SnellsLawAt45DegreesIntoGlass) {
    // Incidence 45 degrees in the x-z plane onto the plane z = 0 from above, n 1 -> 1.5.
    Vec3 d = normalize(Vec3(1, 0, -1));
    Vec3 t;
    ASSERT_TRUE(refract(d, {0, 0, 1}, 1 / 1.5, t));
    double sinT = std::sqrt(0.5) / 1.5;  // 0.4714
    EXPECT_NEAR(t.x, sinT, 1e-12);
    EXPECT_NEAR(t.y, 0, 1e-12);
    EXPECT_NEAR(t.z, -std::sqrt(1 - sinT * sinT), 1e-12);
    EXPECT_NEAR(length(t), 1, 1e-12);
}

TEST(Refract, NormalIncidenceGoesStraightThrough) {
    Vec3 t;
    ASSERT_TRUE(refract({0, 0, -1}, {0, 0, 1}, 1 / 1.33, t));
    EXPECT_NEAR(t.z, -1, 1e-15);
    EXPECT_NEAR(t.x, 0, 1e-15);
}

TEST(Refract, LeavingGlassBendsAwayFromTheNormalAndReversesEntering) {
    Vec3 in = normalize(Vec3(0.3, 0.2, -1)), inside, out;
    ASSERT_TRUE(refract(in, {0, 0, 1}, 1 / 1.5, inside));
    // Out through a parallel face: the original direction again.
    ASSERT_TRUE(refract(inside, {0, 0, 1}, 1.5, out));
    EXPECT_NEAR(out.x, in.x, 1e-12);
    EXPECT_NEAR(out.y, in.y, 1e-12);
    EXPECT_NEAR(out.z, in.z, 1e-12);
}

TEST(Refract, TotalInternalReflectionBeyondTheCriticalAngle) {
    // Glass to air: critical angle asin(1/1.5) = 41.81 degrees.
    double critical = std::asin(1 / 1.5);
    auto at = [](double angle) { return Vec3(std::sin(angle), 0, -std::cos(angle)); };
    Vec3 t;
    EXPECT_TRUE(refract(at(critical - 0.01), {0, 0, 1}, 1.5, t));
    EXPECT_FALSE(refract(at(critical + 0.01), {0, 0, 1}, 1.5, t));
    EXPECT_FALSE(refract(at(60 * kPi / 180), {0, 0, 1}, 1.5, t));
}

TEST(Fresnel, NormalIncidenceIsTheSquaredIndexRatio) {
    EXPECT_NEAR(fresnelDielectric(1, 1 / 1.5), 0.04, 1e-12);  // ((1.5 - 1) / (1.5 + 1))^2
    EXPECT_NEAR(fresnelDielectric(1, 1.5), 0.04, 1e-12);      // the same from inside
    EXPECT_NEAR(fresnelDielectric(1, 1 / 1.333), std::pow(0.333 / 2.333, 2), 1e-12);
}

TEST(Fresnel, MatchedIndicesReflectNothing) {
    for (double c : {0.1, 0.5, 1.0}) EXPECT_NEAR(fresnelDielectric(c, 1), 0, 1e-15);
}

TEST(Fresnel, GrazingIncidenceReflectsEverything) {
    EXPECT_NEAR(fresnelDielectric(0, 1 / 1.5), 1, 1e-12);
    EXPECT_GT(fresnelDielectric(0.01, 1 / 1.5), 0.9);
}

TEST(Fresnel, AHandComputedObliqueCase) {
    // 60 degrees from air into n = 1.5: cosT = sqrt(1 - (sin60 / 1.5)^2) = 0.8165.
    double cosI = 0.5, cosT = std::sqrt(1 - 0.75 / 2.25);
    double rs = (cosI - 1.5 * cosT) / (cosI + 1.5 * cosT);  // -0.4202
    double rp = (1.5 * cosI - cosT) / (1.5 * cosI + cosT);  // -0.0420
    EXPECT_NEAR(fresnelDielectric(cosI, 1 / 1.5), 0.5 * (rs * rs + rp * rp), 1e-12);
    EXPECT_NEAR(fresnelDielectric(cosI, 1 / 1.5), 0.0891, 1e-4);
}

TEST(Fresnel, TotalInternalReflectionIsOne) {
    EXPECT_EQ(fresnelDielectric(std::cos(60 * kPi / 180), 1.5), 1.0);
}

TEST(Fresnel, ReciprocalAcrossTheBoundary) {
    // The same pair of angles seen from either side reflects the same fraction.
    double cosI = 0.8, eta = 1 / 1.5;
    double cosT = std::sqrt(1 - eta * eta * (1 - cosI * cosI));
    EXPECT_NEAR(fresnelDielectric(cosI, eta), fresnelDielectric(cosT, 1 / eta), 1e-12);
}

/// Integrates f over the hemisphere z > 0 by the midpoint rule in (cos theta, phi).
template <typename F>
double hemisphereIntegral(F f, int n = 400) {
    double sum = 0;
    for (int i = 0; i < n; ++i) {
        double z = (i + 0.5) / n;
        double r = std::sqrt(1 - z * z);
        for (int j = 0; j < n; ++j) {
            double phi = 2 * kPi * (j + 0.5) / n;
            sum += f(Vec3(r * std::cos(phi), r * std::sin(phi), z));
        }
    }
    return sum * (1.0 / n) * (2 * kPi / n);
}

TEST(Ggx, DistributionIsNormalisedOverProjectedArea) {
    for (double alpha : {0.2, 0.5, 1.0}) {
        Ggx g{alpha};
        // Small alpha concentrates D near z = 1: refine the grid there.
        double integral = hemisphereIntegral([&](const Vec3& h) { return g.d(h) * h.z; }, 2000);
        EXPECT_NEAR(integral, 1, 0.01) << "alpha " << alpha;
    }
}

TEST(Ggx, MaskingIsOneAtNormalIncidenceAndFallsAtGrazing) {
    Ggx g{0.5};
    EXPECT_NEAR(g.g1({0, 0, 1}), 1, 1e-12);
    EXPECT_LT(g.g1(normalize(Vec3(1, 0, 0.05))), 0.5);
    EXPECT_EQ(g.g1({0, 0, -1}), 0);
}

TEST(Ggx, VisibleNormalsFollowTheirDistribution) {
    // The distribution of visible normals is D_wo(h) = G1(wo) max(0, wo.h) D(h) / wo.z; the
    // mean of h.z over samples must match its integral.
    Ggx g{0.4};
    Vec3 wo = normalize(Vec3(0.6, 0.2, 0.5));
    double expected = hemisphereIntegral(
        [&](const Vec3& h) { return h.z * g.g1(wo) * std::max(0.0, dot(wo, h)) * g.d(h) / wo.z; },
        1000);
    double mass = hemisphereIntegral(
        [&](const Vec3& h) { return g.g1(wo) * std::max(0.0, dot(wo, h)) * g.d(h) / wo.z; }, 1000);
    EXPECT_NEAR(mass, 1, 0.01);
    Rng rng(7);
    const int n = 200000;
    double sum = 0, sum2 = 0;
    for (int i = 0; i < n; ++i) {
        Vec3 h = g.sampleVisibleNormal(wo, rng.uniform(), rng.uniform());
        ASSERT_NEAR(length(h), 1, 1e-9);
        ASSERT_GE(dot(h, wo), -1e-9) << "a sampled normal faces away from wo";
        sum += h.z;
        sum2 += h.z * h.z;
    }
    double mean = sum / n, se = std::sqrt((sum2 / n - mean * mean) / n);
    EXPECT_NEAR(mean, expected, 4 * se + 1e-3) << "standard error " << se;
}

TEST(Ggx, SmallRoughnessSamplesNearTheMirrorDirection) {
    // GGX has long tails: P(theta_h > theta) is about alpha^2 / tan^2(theta). With alpha
    // 0.01, fewer than 5% of normals lie beyond 0.05 rad, so 90% of directions must lie
    // within 0.1 of the mirror direction; at alpha 0.5 most do not.
    auto nearMirror = [](double alpha) {
        Ggx g{alpha};
        Vec3 wo = normalize(Vec3(0.5, 0, 1));
        Vec3 mirror(-wo.x, -wo.y, wo.z);
        Rng rng(3);
        int near = 0;
        for (int i = 0; i < 1000; ++i) {
            Vec3 h = g.sampleVisibleNormal(wo, rng.uniform(), rng.uniform());
            near += length(h * (2 * dot(wo, h)) - wo - mirror) < 0.1;
        }
        return near / 1000.0;
    };
    EXPECT_GT(nearMirror(0.01), 0.9);
    EXPECT_LT(nearMirror(0.5), 0.3);
}

}  // namespace
}  // namespace glint
