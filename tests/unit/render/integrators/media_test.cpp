// Participating media (render/integrators/media.h and the path tracer's use of them): the phase function,
// delta and ratio tracking against Beer-Lambert, a constant grid against the homogeneous
// medium, and rendered images against analytic answers: a slab's transmittance, single
// scattering of a point light in fog against quadrature, and a white furnace of a scattering
// ball of albedo 1.

#include "glint/render/integrators/media.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>

#include "glint/math/mat4.h"
#include "glint/render/renderer.h"
#include "unit/statistics.h"
#include "unit/test_support.h"

namespace glint {
namespace {

constexpr double kPi = std::numbers::pi;

TEST(HenyeyGreenstein, IsNormalisedAndSampledWithItsOwnDensity) {
    for (double g : {-0.7, 0.0, 0.3, 0.9}) {
        const HenyeyGreenstein hg{g};
        const Vec3 wo = normalize(Vec3(0.3, -0.4, 0.8));
        // Over the sphere, in the frame of the travel direction: 2 pi integral of p d(cos).
        const double total = 2 * kPi *
                             test::integrate(
                                 [&](double c) {
                                     const Frame f(-wo);
                                     const double s = std::sqrt(1 - c * c);
                                     return hg.eval(wo, f.toWorld(Vec3(s, 0, c)));
                                 },
                                 -1, 1, 1e-10);
        EXPECT_NEAR(total, 1, 1e-6) << g;
        // Sampled cosines against the density's distribution: 10 bins of cos theta.
        Rng rng(11);
        constexpr int kBins = 10, kDraws = 200000;
        std::vector<double> observed(kBins, 0), expected(kBins, 0);
        test::MeanEstimate meanCos;
        for (int k = 0; k < kDraws; ++k) {
            const Vec3 wi = hg.sample(wo, {rng.uniform(), rng.uniform()});
            const double c = dot(-wo, wi);
            meanCos.add(c);
            observed[std::clamp(static_cast<int>((c + 1) / 2 * kBins), 0, kBins - 1)] += 1;
        }
        for (int b = 0; b < kBins; ++b) {
            const double c0 = -1 + 2.0 * b / kBins, c1 = c0 + 2.0 / kBins;
            expected[b] = kDraws * 2 * kPi *
                          test::integrate(
                              [&](double c) {
                                  const Frame f(-wo);
                                  const double s = std::sqrt(1 - c * c);
                                  return hg.eval(wo, f.toWorld(Vec3(s, 0, c)));
                              },
                              c0, c1, 1e-10);
        }
        EXPECT_GT(test::chiSquareTest(observed, expected).pValue, 1e-4) << g;
        // Henyey-Greenstein's defining property: the mean cosine is g.
        EXPECT_NEAR(meanCos.mean(), g, 4 * meanCos.standardError()) << g;
    }
}

Medium chromaticFog() {
    Medium m;
    m.sigmaA = Vec3(0.2, 0.05, 0.4);
    m.sigmaS = Vec3(0.5, 1.0, 0.1);
    return m;
}

TEST(MediumTracking, DeltaTrackingPassesASlabWithBeerLambertsTransmittanceInEveryChannel) {
    const Medium m = chromaticFog();
    const Ray ray{Vec3(0), Vec3(0, 0, 2), 0, kInfinity};  // not unit: distances are 2 t
    const double tEnd = 0.7;                              // 1.4 units of length
    Rng rng(5);
    std::array<test::MeanEstimate, 3> passed, scattered;
    for (int k = 0; k < 400000; ++k) {
        Vec3 beta(1);
        const MediumEvent e = sampleMedium(m, ray, tEnd, rng, beta);
        for (int c = 0; c < 3; ++c) {
            passed[c].add(e.kind == MediumEvent::Kind::Passed ? beta[c] : 0);
            scattered[c].add(e.kind == MediumEvent::Kind::Scattered ? beta[c] : 0);
        }
    }
    const Vec3 st = m.sigmaT();
    for (int c = 0; c < 3; ++c) {
        const double tr = std::exp(-st[c] * 1.4);
        EXPECT_NEAR(passed[c].mean(), tr, 4 * passed[c].standardError() + 1e-4) << c;
        // What scatters within the slab: the single-scattering albedo of what does not pass.
        const double s = m.sigmaS[c] / st[c] * (1 - tr);
        EXPECT_NEAR(scattered[c].mean(), s, 4 * scattered[c].standardError() + 1e-4) << c;
    }
    const Vec3 exact = mediumTransmittance(m, ray, tEnd, rng);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(exact[c], std::exp(-st[c] * 1.4), 1e-12);
}

TEST(MediumTracking, AConstantGridIsTheHomogeneousMediumInsideItsBoxAndNothingOutside) {
    Medium grid = chromaticFog();
    auto g = std::make_shared<DensityGrid>();
    g->nx = g->ny = g->nz = 4;
    g->density.assign(64, 2.0f);
    // Index [0, 4]^3 placed as the box [-1, 1]^3 (scaled by 0.5, moved by -1).
    grid.grid = g;
    grid.densityBound = 2;
    grid.worldFromIndex =
        *Transform::fromMatrix(Mat4::translate(-1, -1, -1) * Mat4::scale(0.5, 0.5, 0.5));
    Medium doubled = chromaticFog();
    doubled.sigmaA = doubled.sigmaA * 2.0;
    doubled.sigmaS = doubled.sigmaS * 2.0;
    // Along x through the middle of the box, from outside: only [-0.5, 0.5] of it is deep
    // enough inside to have the full density; trilinear filtering ramps it at the faces, so
    // compare a ray that starts and ends well inside, and one that misses the box.
    const Ray inside{Vec3(-0.6, 0, 0), Vec3(1, 0, 0), 0, kInfinity};
    Rng rng(9);
    std::array<test::MeanEstimate, 3> ratio;
    for (int k = 0; k < 100000; ++k) {
        const Vec3 t = mediumTransmittance(grid, inside, 1.2, rng);
        for (int c = 0; c < 3; ++c) ratio[c].add(t[c]);
    }
    const Vec3 exact = mediumTransmittance(doubled, inside, 1.2, rng);
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(ratio[c].mean(), exact[c], 4 * ratio[c].standardError() + 1e-4) << c;
    const Ray missing{Vec3(-3, 2, 0), Vec3(1, 0, 0), 0, kInfinity};
    EXPECT_EQ(mediumTransmittance(grid, missing, 6, rng), Vec3(1));
    Vec3 beta(1);
    EXPECT_EQ(sampleMedium(grid, missing, 6, rng, beta).kind, MediumEvent::Kind::Passed);
    EXPECT_EQ(beta, Vec3(1));
}

/// A sparse grid of 40 x 20 x 12 voxels, placed rotated and scaled: empty but for a dense
/// slab with holes at x in [16, 24) and a few single voxels elsewhere (what a majorant grid is
/// for).
std::shared_ptr<DensityGrid> sparseGrid() {
    auto g = std::make_shared<DensityGrid>();
    g->nx = 40;
    g->ny = 20;
    g->nz = 12;
    g->density.assign(size_t(40) * 20 * 12, 0.0f);
    for (int k = 0; k < 12; ++k)
        for (int j = 0; j < 20; ++j)
            for (int i = 16; i < 24; ++i)
                g->density[(size_t(k) * 20 + j) * 40 + i] = (i + j + k) % 5 == 0 ? 0.0f : 3.0f;
    g->density[(size_t(3) * 20 + 5) * 40 + 2] = 6;
    g->density[(size_t(11) * 20 + 19) * 40 + 39] = 1;
    g->density[(size_t(6) * 20 + 10) * 40 + 31] = 0.5f;
    return g;
}

TEST(MajorantGrid, BoundsTheInterpolatedDensityEverywhereInEachBlock) {
    const auto g = sparseGrid();
    const MajorantGrid majorants(*g);
    EXPECT_EQ(majorants.nx, 5);
    EXPECT_EQ(majorants.ny, 3);
    EXPECT_EQ(majorants.nz, 2);
    Rng rng(17);
    int tight = 0;
    for (int n = 0; n < 200000; ++n) {
        const Vec3 p(rng.uniform() * 40, rng.uniform() * 20, rng.uniform() * 12);
        const double d = g->lookup(p);
        const int a = std::min(int(p.x / 8), 4), b = std::min(int(p.y / 8), 2),
                  c = std::min(int(p.z / 8), 1);
        ASSERT_LE(d, majorants.at(a, b, c) + 1e-6) << p.x << " " << p.y << " " << p.z;
        tight += d > 0.9 * majorants.at(a, b, c);
    }
    EXPECT_GT(tight, 0);
    // Blocks hold what reaches into them, and empty ones are empty.
    EXPECT_EQ(majorants.at(0, 0, 0), 6.0f);  // the voxel (2, 5, 3)
    EXPECT_EQ(majorants.at(0, 1, 1), 0.0f);
    EXPECT_EQ(majorants.at(1, 2, 1), 3.0f);  // x in [8, 16]: the slab's voxel 16 reads from 15.5
    EXPECT_EQ(majorants.at(4, 0, 0), 0.0f);
    EXPECT_EQ(majorants.at(4, 1, 0), 0.5f);  // the voxel (31, 10, 6) reads up to x = 32.5
}

TEST(MediumTracking, TrackingBlockByBlockAgreesWithTheOpticalDepthAlongTheRay) {
    // Ratio tracking's transmittance and delta tracking's chance of passing an absorbing
    // medium, with the majorant grid and with the one global bound, against exp(-tau) with
    // tau integrated along the ray by the midpoint rule.
    Medium m;
    m.sigmaA = Vec3(0.5, 0.2, 0.8);
    m.grid = sparseGrid();
    m.densityBound = 6;
    m.worldFromIndex = *Transform::fromMatrix(
        Mat4::translate(0.3, -1, 2) * Mat4::rotate(1, 2, 0.5, 23) * Mat4::scale(0.05, 0.05, 0.05));
    Medium global = m;
    m.majorants = std::make_shared<const MajorantGrid>(*m.grid);
    const Vec3 from = m.worldFromIndex.point(Vec3(-3, 4, 2)),
               to = m.worldFromIndex.point(Vec3(43, 15, 10));
    const Ray ray{from, (to - from) * 0.5, 0, kInfinity};  // not unit
    const double tEnd = 2;
    double tau = 0;
    constexpr int kSteps = 200000;
    for (int s = 0; s < kSteps; ++s) {
        const double t = (s + 0.5) * tEnd / kSteps;
        tau += m.density(ray.origin + ray.dir * t) * tEnd / kSteps * length(ray.dir);
    }
    ASSERT_GT(tau, 0.3);
    for (const Medium* medium : {&m, &global}) {
        Rng rng(23);
        std::array<test::MeanEstimate, 3> ratio, passed;
        for (int k = 0; k < 100000; ++k) {
            const Vec3 tr = mediumTransmittance(*medium, ray, tEnd, rng);
            Vec3 beta(1);
            const bool through =
                sampleMedium(*medium, ray, tEnd, rng, beta).kind == MediumEvent::Kind::Passed;
            for (int c = 0; c < 3; ++c) {
                ratio[c].add(tr[c]);
                passed[c].add(through ? beta[c] : 0);
            }
        }
        for (int c = 0; c < 3; ++c) {
            const double expected = std::exp(-m.sigmaA[c] * tau);
            EXPECT_NEAR(ratio[c].mean(), expected, 4 * ratio[c].standardError() + 1e-3) << c;
            EXPECT_NEAR(passed[c].mean(), expected, 4 * passed[c].standardError() + 1e-3) << c;
        }
    }
}

/// The mean red value of a render of `text` at `spp` samples per pixel.
double meanRender(const std::string& text, int spp) {
    auto scene = test::preparedScene(text);
    RenderOptions o;
    o.spp = spp;
    o.threads = 2;
    o.seed = 3;
    const Film film = render(*scene, o).film;
    double sum = 0;
    for (int y = 0; y < film.height(); ++y)
        for (int x = 0; x < film.width(); ++x) sum += film.at(x, y).x;
    return sum / (film.width() * film.height());
}

TEST(MediaRender, AnAbsorbingBoxDimsTheLightBehindItByBeerLambert) {
    // An emissive square seen through a box of absorbing medium 2 units deep (its boundary an
    // interface): the image is its emission times exp(-sigma_a 2) on average.
    const std::string scene = R"(
        size 8 8
        integrator path
        camera 0 0 5  0 0 0  0 1 0  5
        maxdepth 4
        quadLight -2 -2 -3  4 0 0  0 4 0  1 1 1
        medium ink absorption 0.4 0.4 0.4
        interior ink interface
        box -1 -1 -1  1 1 1
    )";
    // Delta tracking absorbs whole paths: each sample is 0 or 1, with probability exp(-0.8)
    // of 1; 64 pixels x 256 samples give a standard error of 0.004.
    EXPECT_NEAR(meanRender(scene, 256), std::exp(-0.8), 0.016);
}

TEST(MediaRender, SingleScatteringOfAPointLightInFogMatchesQuadrature) {
    // A camera ray along -z through homogeneous fog, a point light beside it at distance h:
    // with one scattering event (maxdepth 1) the pixel is
    //   L = integral sigma_s exp(-sigma_t t) p(theta) I exp(-sigma_t r) / r^2 dt,
    // r the distance from the ray's point to the light, p isotropic 1 / (4 pi).
    const double sigmaS = 0.3, sigmaA = 0.1, h = 1, intensity = 2;
    const std::string scene = R"(
        size 1 1
        integrator path
        camera 0 0 0  0 0 -1  0 1 0  0.05
        maxdepth 1
        medium haze scattering 0.3 0.3 0.3 absorption 0.1 0.1 0.1
        fog haze
        attenuation 0 0 1
        point 0 1 -2  2 2 2
    )";
    const double st = sigmaS + sigmaA;
    const double expected = test::integrate(
        [&](double t) {
            const double r2 = h * h + (t - 2) * (t - 2);
            return sigmaS * std::exp(-st * t) / (4 * kPi) * intensity *
                   std::exp(-st * std::sqrt(r2)) / r2;
        },
        0, 200, 1e-12);
    EXPECT_NEAR(meanRender(scene, 20000), expected, 0.02 * expected);
}

TEST(MediaRender, AScatteringBallOfAlbedoOneKeepsAWhiteFurnaceWhite) {
    // A ball of medium that scatters and never absorbs, its boundary an interface, under a
    // uniform white sky: whatever paths do inside, they leave with the sky's radiance.
    const std::string scene = R"(
        size 6 6
        integrator path
        camera 0 0 4  0 0 0  0 1 0  30
        maxdepth 400
        background 1 1 1
        medium cloud scattering 3 3 3 g 0.4
        interior cloud interface
        sphere 0 0 0 1
    )";
    EXPECT_NEAR(meanRender(scene, 64), 1, 0.02);
}

TEST(MediaRender, WhittedSeesAndLightsThroughInterfaceSurfaces) {
    // The course's integrator renders no media: a medium's interface box in front of a lit
    // sphere changes nothing, for camera rays and shadow rays alike.
    const std::string lit = R"(
        size 16 16
        camera 0 0 5  0 0 0  0 1 0  30
        point 0 4 4  1 1 1
        diffuse 0.8 0.4 0.2
        sphere 0 0 0 1
        medium ink absorption 0.4 0.4 0.4
    )";
    const double bare = meanRender(lit, 1);
    EXPECT_GT(bare, 0.05);
    EXPECT_NEAR(meanRender(lit + "interior ink interface\nbox -2 -2 -2  2 2 2\n", 1), bare, 1e-6);
    EXPECT_NEAR(meanRender(lit + "interior ink interface\nbox -0.5 2 1  0.5 2.5 2\n", 1), bare,
                1e-6);
}

}  // namespace
}  // namespace glint
