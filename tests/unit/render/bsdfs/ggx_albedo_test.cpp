// The table of GGX directional albedos (ggx_albedo.h): its entries against a quadrature of
// optics.h's lobe independent of the generator's, the lookup against the entries, and the
// averages against the interpolated albedo they stand for.

#include "glint/render/bsdfs/ggx_albedo.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "glint/render/bsdfs/optics.h"
#include "unit/statistics.h"

namespace glint {
namespace {

using namespace ggx_albedo_table;
constexpr double kPi = std::numbers::pi;

/// E(mu, alpha) by quadrature over the half-vector h (the generator integrates over the disk of
/// visible normals instead): E = integral of D(h) G1(o) G1(i) (o.h) / cos_o dh, i the mirror of
/// o about h, as dwi = 4 (o.h) dh. theta_h is reached through y in [0, 1), tan theta_h =
/// alpha sqrt(y / (1 - y)), under which GGX's D cos theta_h dh is dy dphi / (2 pi): the peak of a
/// smooth surface's normals is spread over the interval.
double albedoOverHalfVectors(double mu, double alpha) {
    Ggx ggx{alpha};
    Vec3 o(std::sqrt(1 - mu * mu), 0, mu);
    auto overPhi = [&](double y) {
        double t = alpha * std::sqrt(y / (1 - y));  // tan theta_h
        double cosH = 1 / std::sqrt(1 + t * t), sinH = t * cosH;
        // d theta_h / dy, from tan theta = alpha sqrt(y / (1 - y)).
        double dTheta = cosH * cosH * alpha / (2 * std::sqrt(y) * std::pow(1 - y, 1.5));
        auto f = [&](double phi) {
            Vec3 h(sinH * std::cos(phi), sinH * std::sin(phi), cosH);
            double oh = dot(o, h);
            if (!(oh > 0)) return 0.0;
            Vec3 i = h * (2 * oh) - o;
            return ggx.d(h) * ggx.g1(o) * ggx.g1(i) * oh / mu * sinH * dTheta;
        };
        return 2 * test::integrate(f, 0, kPi, 1e-11, 8);  // o in the xz-plane: symmetric in phi
    };
    // The steep normals that matter at grazing angles lie at 1 - y ~ alpha^2: panels crowd
    // there. y = 0 and 1 are not evaluated well (0 / 0): stop just short of them.
    double sum = 0, a = 1e-14;
    for (double gap = 0.1; gap >= 1e-12; gap /= 10) {
        sum += test::integrate(overPhi, a, 1 - gap, 1e-10, 4);
        a = 1 - gap;
    }
    return sum;
}

TEST(GgxAlbedoTable, EntriesMatchAnIndependentQuadratureOfTheLobe) {
    for (int r : {1, 12, 30, 48, 60, 72, 84, 95})
        for (int j : {0, 3, 10, 18, 26, 31}) {
            double alpha = rowAlpha(r), mu = columnCosine(j, alpha);
            if (mu == 0) mu = 1e-9;  // the limit at grazing
            double e = albedoOverHalfVectors(mu, alpha);
            EXPECT_NEAR(kAlbedo[r][j], e, 2e-6)
                << "row " << r << " (alpha " << alpha << "), column " << j << " (mu " << mu << ")";
        }
    // Two values known in closed form: the mirror's 1, and at alpha = 1 from normal incidence
    // 1 - ln 2 (GGX with alpha = 1 has a constant D: the visible normals within 45 degrees of
    // the normal reflect wo above the surface, and the mean of G1(wi) over them is this).
    EXPECT_EQ(kAlbedo[0][0], 1.0f);
    EXPECT_NEAR(kAlbedo[kRows - 1][kColumns - 1], 1 - std::log(2.0), 1e-7);
}

TEST(GgxAlbedoTable, TheLookupReproducesTheEntriesAndInterpolatesBetweenThem) {
    for (int r : {0, 1, 2, 40, 95})
        for (int j : {0, 7, 31}) {
            double alpha = rowAlpha(r);
            EXPECT_NEAR(GgxAlbedo(alpha)(columnCosine(j, alpha)), kAlbedo[r][j], 1e-6)
                << r << " " << j;
        }
    // alpha = 0 is the mirror, which loses nothing; out-of-range inputs are clamped.
    EXPECT_EQ(GgxAlbedo(0)(0.3), 1);
    EXPECT_EQ(GgxAlbedo(0).average(), 1);
    EXPECT_EQ(GgxAlbedo(2)(0.5), GgxAlbedo(1)(0.5));
    EXPECT_EQ(GgxAlbedo(0.4)(1.5), GgxAlbedo(0.4)(1));
    // Between entries, within the error the generator measured (at points it did not use).
    for (double alpha : {0.0023, 0.047, 0.15, 0.33, 0.71, 0.93})
        for (double mu : {0.013, 0.2, 0.55, 0.9, 0.995}) {
            double e = albedoOverHalfVectors(mu, alpha);
            EXPECT_NEAR(GgxAlbedo(alpha)(mu), e, kMaxError) << alpha << " " << mu;
        }
    std::printf("table error bound: %.2g (alpha >= %.3g), %.2g below\n", kMaxError, kAlpha1,
                kMaxErrorBelowRow1);
}

// The white furnace of the compensated conductor holds exactly (for the table's E) only if
// E_avg is the average of the interpolated E, not of the true one.
TEST(GgxAlbedoTable, TheAverageIsExactlyThatOfTheInterpolatedAlbedo) {
    for (double alpha : {0.0, 4e-4, 1e-3, 0.0123, 0.1, 0.37, 0.61, 0.999, 1.0}) {
        GgxAlbedo e(alpha);
        // 2 integral E(mu) mu dmu over mu = sin g: the interpolant is smooth in g between its
        // columns.
        double average =
            2 *
            test::integrate([&](double g) { return e(std::sin(g)) * std::sin(g) * std::cos(g); }, 0,
                            kPi / 2, 1e-13, 64);
        EXPECT_NEAR(e.average(), average, 1e-10) << alpha;
        EXPECT_LE(e.average(), 1);
    }
}

}  // namespace
}  // namespace glint
