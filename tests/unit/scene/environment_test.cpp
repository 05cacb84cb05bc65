// The environment map: its mapping (against Cycles' formula and at known texels), rotation,
// lookups, and its sampling: sample() against pdf() by a chi-square test over the sphere, the
// density's integral, sample() agreeing with eval() and pdf(), and an unbiased estimate.

#include "glint/scene/environment.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "glint/math/rng.h"
#include "glint/scene/light_spec.h"
#include "unit/statistics.h"
#include "unit/test_support.h"

namespace glint {
namespace {

constexpr double kPi = std::numbers::pi;

/// A map whose texel (x, y) is (x + 1, y + 1, x * y + 0.5) / 8: every texel distinct.
EnvironmentMap indexMap(int w, int h, double rotation = 0) {
    std::vector<float> rgb;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (double v : {x + 1.0, y + 1.0, x * y + 0.5})
                rgb.push_back(static_cast<float>(v / 8));
    return EnvironmentMap(w, h, std::move(rgb), 1, rotation);
}

/// A non-uniform test map: a sky brighter towards the top, a dark band, a black patch (texels
/// of radiance 0) and a small bright "sun" of one texel, on 16 x 8 texels.
EnvironmentMap skyMap(double scale = 1, double rotation = 0) {
    const int w = 16, h = 8;
    std::vector<float> rgb;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            Vec3 c = Vec3(0.2, 0.3, 0.6) * (1.0 + (h - y)) + Vec3(0.05 * x, 0, 0);
            if (y == 5) c = c * 0.1;
            if (x >= 9 && x <= 11 && y >= 6) c = Vec3(0);
            if (x == 4 && y == 2) c = Vec3(40, 30, 20);
            for (int k = 0; k < 3; ++k) rgb.push_back(static_cast<float>(c[k]));
        }
    return EnvironmentMap(w, h, std::move(rgb), scale, rotation);
}

/// A uniformly distributed unit direction.
Vec3 randomDirection(Rng& rng) {
    double z = 1 - 2 * static_cast<double>(rng.uniform());
    double phi = 2 * kPi * static_cast<double>(rng.uniform());
    double r = std::sqrt(std::max(0.0, 1 - z * z));
    return {r * std::cos(phi), z, r * std::sin(phi)};
}

/// The direction at image coordinates (s, t) by the documented formula, rotation 0.
Vec3 documentedDirection(double s, double t) {
    double theta = kPi * t, phi = 2 * kPi * s - kPi;
    return {std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi)};
}

TEST(EnvironmentMap, ImageCoordinatesAreCyclesEquirectangularAfterTheAxisChange) {
    // Cycles (kernel/geom: direction_to_equirectangular with its default range) for a Blender
    // direction b: u = (atan2(b.y, b.x) - pi) / (-2 pi), v = (acos(b.z) - pi) / (-pi), v up from
    // the image's bottom row. Blender (x, y, z) = Glint (x, -z, y).
    EnvironmentMap map = indexMap(8, 4);
    Rng rng(3);
    for (int i = 0; i < 1000; ++i) {
        Vec3 d = randomDirection(rng);
        Vec3 b(d.x, -d.z, d.y);
        double u = (std::atan2(b.y, b.x) - kPi) / (-2 * kPi);
        double v = (std::acos(b.z) - kPi) / (-kPi);
        Point2 st = map.imageCoordinates(d);
        double du = std::remainder(st.x - u, 1.0);  // u = 1 and s = 0 are the same column
        EXPECT_NEAR(du, 0, 1e-12) << d.x << " " << d.y << " " << d.z;
        EXPECT_NEAR(st.y, 1 - v, 1e-12);
    }
}

TEST(EnvironmentMap, KnownDirectionsSeeKnownTexels) {
    // 4 x 2 texels: centres at s = 1/8, 3/8, 5/8, 7/8 (phi = -3pi/4, -pi/4, pi/4, 3pi/4) and
    // t = 1/4, 3/4 (45 degrees above and below the horizon). Bilinear lookups at texel
    // centres give the texel itself.
    EnvironmentMap map = indexMap(4, 2);
    const double r = std::sqrt(0.5);
    struct Case {
        Vec3 dir;
        int x, y;
    } cases[] = {
        {{0.5, r, 0.5}, 2, 0},     // up, +x, +z: right of the image centre, top row
        {{0.5, r, -0.5}, 1, 0},    // up, +x, -z: left of the centre
        {{-0.5, r, -0.5}, 0, 0},   // up, -x, -z: the left edge
        {{-0.5, r, 0.5}, 3, 0},    // up, -x, +z: the right edge
        {{0.5, -r, 0.5}, 2, 1},    // below the horizon: the bottom row
        {{-0.5, -r, -0.5}, 0, 1},  //
    };
    for (const Case& c : cases) {
        test::expectNear(map.eval(c.dir), map.texel(c.x, c.y), 1e-12);
        Point2 st = map.imageCoordinates(c.dir);
        EXPECT_NEAR(st.x, (c.x + 0.5) / 4, 1e-12);
        EXPECT_NEAR(st.y, (c.y + 0.5) / 2, 1e-12);
    }
    // Every texel centre of a larger map, by the documented formula.
    EnvironmentMap big = indexMap(12, 6);
    for (int y = 0; y < 6; ++y)
        for (int x = 0; x < 12; ++x)
            test::expectNear(big.eval(documentedDirection((x + 0.5) / 12, (y + 0.5) / 6)),
                             big.texel(x, y), 1e-12);
    // Straight up and down read the top and bottom rows; +x the image centre, between the
    // four middle texels of a 4 x 2 map; -x the left and right edges, wrapping around.
    EXPECT_NEAR(map.imageCoordinates({0, 1, 0}).y, 0, 1e-15);
    EXPECT_NEAR(map.imageCoordinates({0, -1, 0}).y, 1, 1e-15);
    test::expectNear(map.eval({1, 0, 0}),
                     (map.texel(1, 0) + map.texel(2, 0) + map.texel(1, 1) + map.texel(2, 1)) * 0.25,
                     1e-12);
    test::expectNear(map.eval({-1, 0, 0}),
                     (map.texel(0, 0) + map.texel(3, 0) + map.texel(0, 1) + map.texel(3, 1)) * 0.25,
                     1e-12);
    // direction() inverts imageCoordinates().
    Rng rng(5);
    for (int i = 0; i < 100; ++i) {
        Vec3 d = randomDirection(rng);
        test::expectNear(map.direction(map.imageCoordinates(d)), d, 1e-12);
    }
}

TEST(EnvironmentMap, LookupsAreBilinearAndScaled) {
    EnvironmentMap map = indexMap(4, 2);
    // Halfway between the centres of texels 1 and 2 of the top row, at its centre's height.
    Vec3 d = documentedDirection(0.5, 0.25);
    test::expectNear(map.eval(d), (map.texel(1, 0) + map.texel(2, 0)) * 0.5, 1e-12);
    // A quarter of the way from texel 3 to texel 0 across the seam.
    d = documentedDirection(7.5 / 8, 0.25);
    test::expectNear(map.eval(d), map.texel(3, 0) * 0.75 + map.texel(0, 0) * 0.25, 1e-12);
    std::vector<float> rgb(4 * 2 * 3, 0.5f);
    EnvironmentMap scaled(4, 2, rgb, 3);
    test::expectNear(scaled.eval({0.3, 0.4, 0.5}), Vec3(1.5), 1e-15);
}

TEST(EnvironmentMap, RotationTurnsTheMapAboutUpCounterClockwiseSeenFromAbove) {
    EnvironmentMap map = skyMap(), turned = skyMap(1, 90);
    // rotate 0 1 0 90 takes +x to -z: what the unrotated map shows along +x is seen along -z.
    test::expectNear(turned.eval({0, 0.3, -1}), map.eval({1, 0.3, 0}), 1e-12);
    test::expectNear(turned.eval({1, -0.2, 0}), map.eval({0, -0.2, 1}), 1e-12);
    // In general, eval_turned(R d) = eval(d), and the densities move with it.
    EnvironmentMap odd = skyMap(1, -33.5);
    double c = std::cos(-33.5 * kPi / 180), s = std::sin(-33.5 * kPi / 180);
    Rng rng(9);
    for (int i = 0; i < 200; ++i) {
        Vec3 d = randomDirection(rng);
        Vec3 rd(c * d.x + s * d.z, d.y, -s * d.x + c * d.z);  // R_y(angle) d
        test::expectNear(odd.eval(rd), map.eval(d), 1e-9);
        EXPECT_NEAR(odd.pdf(rd), map.pdf(d), 1e-9 * map.pdf(d));
    }
    // Whole turns change nothing.
    EnvironmentMap full = skyMap(1, 720);
    test::expectNear(full.eval({0.2, 0.5, -0.7}), map.eval({0.2, 0.5, -0.7}), 1e-12);
}

TEST(EnvironmentMap, ConstantMapHasUniformDensity) {
    std::vector<float> rgb(10 * 5 * 3, 0.25f);
    EnvironmentMap map(10, 5, rgb, 2);
    Rng rng(1);
    for (int i = 0; i < 1000; ++i) {
        Vec3 d = randomDirection(rng);
        ASSERT_NEAR(map.pdf(d), 1 / (4 * kPi), 1e-12);
        auto smp = map.sample({rng.uniform(), rng.uniform()});
        ASSERT_TRUE(smp);
        ASSERT_NEAR(smp->pdf, 1 / (4 * kPi), 1e-12);
        ASSERT_NEAR(length(smp->wi), 1, 1e-12);
        ASSERT_NEAR(maxComponent(abs(smp->L - Vec3(0.5))), 0, 1e-12);
    }
    EXPECT_NEAR(map.pdf({0, 1, 0}), 1 / (4 * kPi), 1e-12);  // finite at the poles
    test::expectNear(map.averageRadiance(), Vec3(0.5), 1e-12);
    EXPECT_NEAR(map.power(2), kPi * 4 * 4 * kPi * 0.5, 1e-9);
}

TEST(EnvironmentMap, SampleGivesEvalAndPdfOfItsDirection) {
    EnvironmentMap map = skyMap(1.5, 20);
    Rng rng(2);
    int none = 0;
    for (int i = 0; i < 20000; ++i) {
        auto smp = map.sample({rng.uniform(), rng.uniform()});
        if (!smp) {
            ++none;
            continue;
        }
        ASSERT_NEAR(length(smp->wi), 1, 1e-12);
        ASSERT_EQ(smp->L, map.eval(smp->wi));
        ASSERT_EQ(smp->pdf, map.pdf(smp->wi));
        ASSERT_GT(smp->pdf, 0);
    }
    EXPECT_EQ(none, 0);
}

/// The integral of the map's density over the sphere, by the midpoint rule on a grid in
/// (phi, cos theta), where the solid angle is d phi d cos(theta).
double integrateOverSphere(const EnvironmentMap& map, int nPhi, int nZ) {
    double sum = 0;
    for (int j = 0; j < nZ; ++j) {
        double z = 1 - 2 * (j + 0.5) / nZ, r = std::sqrt(1 - z * z);
        for (int i = 0; i < nPhi; ++i) {
            double phi = 2 * kPi * (i + 0.5) / nPhi;
            sum += map.pdf({r * std::cos(phi), z, r * std::sin(phi)});
        }
    }
    return sum * (2 * kPi / nPhi) * (2.0 / nZ);
}

TEST(EnvironmentMap, DensityIntegratesToOneOverTheSphere) {
    EXPECT_NEAR(integrateOverSphere(skyMap(), 512, 2048), 1, 1e-3);
    EXPECT_NEAR(integrateOverSphere(skyMap(0.5, 47), 512, 2048), 1, 1e-3);
    std::vector<float> black(6 * 3 * 3, 0.0f);  // no radiance: uniform
    EXPECT_NEAR(integrateOverSphere(EnvironmentMap(6, 3, black), 256, 1024), 1, 1e-3);
}

/// Pearson's chi-square test of sample() against pdf(): directions binned on the sphere in
/// (phi, theta) cells, the expected counts integrated from pdf() by the midpoint rule on a
/// sub-grid of each bin.
test::ChiSquareResult chiSquareOverDirections(const EnvironmentMap& map, int samples,
                                              uint64_t seed) {
    const int nPhi = 16, nTheta = 8, sub = 8;
    std::vector<double> observed(nPhi * nTheta, 0), expected(nPhi * nTheta, 0);
    auto bin = [&](const Vec3& d) {
        double phi = std::atan2(d.z, d.x) + kPi;  // [0, 2 pi]
        double theta = std::acos(std::clamp(d.y, -1.0, 1.0));
        int i = std::min(static_cast<int>(phi / (2 * kPi) * nPhi), nPhi - 1);
        int j = std::min(static_cast<int>(theta / kPi * nTheta), nTheta - 1);
        return j * nPhi + i;
    };
    Rng rng(seed);
    for (int k = 0; k < samples; ++k) {
        auto smp = map.sample({rng.uniform(), rng.uniform()});
        if (smp) observed[static_cast<size_t>(bin(smp->wi))] += 1;
    }
    for (int j = 0; j < nTheta; ++j) {
        double z0 = std::cos(kPi * j / nTheta), z1 = std::cos(kPi * (j + 1) / nTheta);
        for (int i = 0; i < nPhi; ++i) {
            double sum = 0;
            for (int b = 0; b < sub; ++b)
                for (int a = 0; a < sub; ++a) {
                    double z = z0 + (z1 - z0) * (b + 0.5) / sub, r = std::sqrt(1 - z * z);
                    double phi = 2 * kPi * (i + (a + 0.5) / sub) / nPhi - kPi;
                    sum += map.pdf({r * std::cos(phi), z, r * std::sin(phi)});
                }
            double solidAngle = (2 * kPi / nPhi) * (z0 - z1);
            expected[static_cast<size_t>(j * nPhi + i)] = sum / (sub * sub) * solidAngle * samples;
        }
    }
    return test::chiSquareTest(observed, expected);
}

TEST(EnvironmentMap, SampleAgreesWithPdfByChiSquare) {
    // Three maps (plain; scaled and rotated by five columns; a small one whose cells are
    // larger than the bins), with the Sidak-corrected level 0.01 overall. The bins' edges
    // include the cells', so that the density is constant within a bin and the midpoint rule
    // integrates it exactly. A million samples a map find a density 1% off (times 1.01 in
    // one hemisphere and 0.99 in the other, or 1.01 everywhere).
    const double level = test::sidak(0.01, 3);
    std::vector<float> small = {0, 0, 0, 1, 2, 3, 0.5f, 0.5f, 0.5f, 4, 0, 0,
                                0, 0, 0, 1, 1, 1, 0,    0,    0,    0, 0, 2};
    const EnvironmentMap maps[] = {skyMap(), skyMap(2, 112.5), EnvironmentMap(4, 2, small)};
    uint64_t seed = 100;
    for (const EnvironmentMap& map : maps) {
        test::ChiSquareResult r = chiSquareOverDirections(map, 1'000'000, ++seed);
        EXPECT_FALSE(r.outsideSupport) << "samples where pdf() is 0";
        EXPECT_GT(r.pValue, level) << "chi2 " << r.chi2 << " over " << r.dof << " dof";
    }
}

TEST(EnvironmentMap, EstimatesOfTheIncidentPowerAreUnbiased) {
    // The integral of luminance over the sphere: by importance sampling (sum of L / pdf) and by
    // fine quadrature of eval(). The sample mean must fall within 4 standard errors.
    EnvironmentMap map = skyMap(1, 12);
    const int nPhi = 1024, nZ = 1024;
    double exact = 0;
    for (int j = 0; j < nZ; ++j) {
        double z = 1 - 2 * (j + 0.5) / nZ, r = std::sqrt(1 - z * z);
        for (int i = 0; i < nPhi; ++i) {
            double phi = 2 * kPi * (i + 0.5) / nPhi;
            exact += luminance(map.eval({r * std::cos(phi), z, r * std::sin(phi)}));
        }
    }
    exact *= (2 * kPi / nPhi) * (2.0 / nZ);
    test::MeanEstimate estimate;
    Rng rng(77);
    for (int k = 0; k < 400000; ++k) {
        auto smp = map.sample({rng.uniform(), rng.uniform()});
        estimate.add(smp ? luminance(smp->L) / smp->pdf : 0.0);
    }
    EXPECT_NEAR(estimate.mean(), exact, 4 * estimate.standardError() + 1e-4 * exact);
    // And the mean the map reports (exact for the bilinear radiance), by the same quadrature.
    EXPECT_NEAR(luminance(map.averageRadiance()), exact / (4 * kPi), 1e-5 * exact / (4 * kPi));
}

TEST(EnvironmentMap, BlackTexelsFarFromLightHaveNoDensity) {
    // One bright texel among black ones: only its cell and its neighbours' (which its bilinear
    // spread reaches) are sampled; elsewhere density and radiance are 0.
    std::vector<float> rgb(8 * 4 * 3, 0.0f);
    rgb[(1 * 8 + 5) * 3 + 1] = 2;  // texel (5, 1), green
    EnvironmentMap map(8, 4, rgb);
    Vec3 far = documentedDirection(1.5 / 8, 3.5 / 4);  // texel (1, 3)
    EXPECT_EQ(map.pdf(far), 0);
    EXPECT_EQ(map.eval(far), Vec3(0));
    Vec3 at = documentedDirection(5.5 / 8, 1.5 / 4);
    EXPECT_GT(map.pdf(at), 0);
    test::expectNear(map.eval(at), Vec3(0, 2, 0), 1e-12);
    Rng rng(4);
    for (int i = 0; i < 10000; ++i) {
        auto smp = map.sample({rng.uniform(), rng.uniform()});
        ASSERT_TRUE(smp);
        Point2 st = map.imageCoordinates(smp->wi);
        ASSERT_GE(st.x * 8, 4);  // within one texel of texel 5 horizontally
        ASSERT_LT(st.x * 8, 7);
        ASSERT_LT(st.y * 4, 3);  // and vertically
    }
}

TEST(EnvironmentMap, BadTexelsReadAsZeroOrTheLargestRadiance) {
    std::vector<float> rgb = {std::nanf(""), -1, INFINITY, 1, 1, 1};
    EnvironmentMap map(2, 1, rgb);
    EXPECT_EQ(map.texel(0, 0), Vec3(0, 0, static_cast<double>(static_cast<float>(kMaxRadiance))));
    EXPECT_TRUE(std::isfinite(map.pdf({1, 0, 0})));
}

TEST(EnvironmentMap, InvalidArgumentsAreRefused) {
    EXPECT_THROW(EnvironmentMap(0, 1, {}), std::invalid_argument);
    EXPECT_THROW(EnvironmentMap(2, 2, std::vector<float>(11)), std::invalid_argument);
    EXPECT_THROW(EnvironmentMap(1, 1, std::vector<float>(3), -1), std::invalid_argument);
    EXPECT_THROW(EnvironmentMap(1, 1, std::vector<float>(3), NAN), std::invalid_argument);
    EXPECT_THROW(EnvironmentMap(1, 1, std::vector<float>(3), 1, INFINITY), std::invalid_argument);
}

}  // namespace
}  // namespace glint
