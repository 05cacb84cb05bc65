// Adaptive sampling: the error estimate, which pixels stop when, and that the image does not
// depend on threads or pieces.

#include "glint/render/adaptive.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "unit/test_support.h"

namespace glint {
namespace {

/// The left half of the image sees a diffuse wall lit by the sky (noisy), the right half the
/// sky itself (exact).
const char* kHalfNoisy =
    "size 16 8\n"
    "integrator path\n"
    "camera 0 0 0  0 0 -1  0 1 0  90\n"
    "background 1 1 1\n"
    "ambient 0 0 0\n"
    "diffuse 0.5 0.5 0.5\n"
    "vertex -100 -100 -4\nvertex 0 -100 -4\nvertex 0 100 -4\nvertex -100 100 -4\n"
    "tri 0 1 2\ntri 0 2 3\n"
    "diffuse 0.8 0.8 0.8\nsphere -2 0 -3 0.8\n";

TEST(PixelError, IsInfiniteBelowTwoSamplesAndZeroForEqualOnes) {
    EXPECT_TRUE(std::isinf(pixelError(Vec3(1), Vec3(1), 1)));
    EXPECT_EQ(pixelError(Vec3(8), Vec3(16), 4), 0);  // four samples of 2
    // Samples 0 and 2 in every channel: mean 1, the mean's standard error 1 per channel:
    // (1 + 1 + 1) / (1e-4 + sqrt(3)).
    EXPECT_NEAR(pixelError(Vec3(2), Vec3(4), 2), 3 / (1e-4 + std::sqrt(3.0)), 1e-12);
}

RenderOptions threads(int n) {
    RenderOptions o;
    o.threads = n;
    return o;
}

TEST(Adaptive, ExactPixelsStopAtTheMinimumAndNoisyOnesGoOn) {
    auto scene = test::preparedScene(kHalfNoisy);
    RenderOptions o = threads(1);
    o.keepSums = true;
    const RenderResult r = renderAdaptive(*scene, o, {0.05, 8, 256, 0});
    ASSERT_TRUE(r.complete);
    int skyMost = 0, wallLeast = 1 << 30;
    for (int y = 0; y < 8; ++y) {
        for (int x = 11; x < 16; ++x) skyMost = std::max(skyMost, int(r.sums.weight(x, y)));
        for (int x = 0; x < 5; ++x) wallLeast = std::min(wallLeast, int(r.sums.weight(x, y)));
    }
    EXPECT_EQ(skyMost, 8);  // stopped at the first check
    EXPECT_GT(wallLeast, 8);
    EXPECT_LE(r.samplesPerPixel, 256);
    EXPECT_GT(r.meanSamplesPerPixel, 8);
    EXPECT_LT(r.meanSamplesPerPixel, 256);
    // The sky is exact whatever the samples.
    EXPECT_EQ(r.film.at(14, 4), Vec3(1));
}

TEST(Adaptive, NoPixelStopsBeforeItsMinimumAndNoneGoesPastTheCap) {
    auto scene = test::preparedScene(kHalfNoisy);
    RenderOptions o = threads(2);
    o.keepSums = true;
    const RenderResult r = renderAdaptive(*scene, o, {1e-4, 24, 40, 0});
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 16; ++x) {
            EXPECT_GE(r.sums.weight(x, y), 24);
            EXPECT_LE(r.sums.weight(x, y), 40);
        }
    // With a threshold no noisy pixel meets, the noisy ones take the cap.
    EXPECT_EQ(r.sums.weight(2, 4), 40);
    EXPECT_EQ(r.samplesPerPixel, 40);
}

TEST(Adaptive, ATimeBudgetCutsTheMinimumTooButLeavesEveryPixelASample) {
    // A budget already spent when the first round ends: that round, one sample of every pixel,
    // is all there is, where the minimum would take 24 (a heavy model on a busy machine).
    auto scene = test::preparedScene(kHalfNoisy);
    RenderOptions o = threads(1);
    o.keepSums = true;
    const RenderResult spent = renderAdaptive(*scene, o, {0.05, 24, 256, 1e-9});
    ASSERT_TRUE(spent.complete);
    EXPECT_EQ(spent.samplesPerPixel, 1);
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 16; ++x) EXPECT_EQ(spent.sums.weight(x, y), 1) << x << " " << y;
    // A budget the minimum fits in: the minimum in rounds from one sample, then as without
    // a budget (the wall's pixels go on to the cap, the exact sky's stop).
    const RenderResult ample = renderAdaptive(*scene, o, {1e-4, 24, 64, 60});
    ASSERT_TRUE(ample.complete);
    EXPECT_EQ(ample.sums.weight(14, 4), 24);
    EXPECT_EQ(ample.sums.weight(2, 4), 64);
    EXPECT_GE(ample.passes, 6);  // 1, 1, 2, 4, 8, 8 to the minimum, then more
}

TEST(Adaptive, TheImageDoesNotDependOnThreadsOrCrops) {
    auto scene = test::preparedScene(kHalfNoisy);
    const AdaptiveOptions a{0.03, 8, 128, 0};
    RenderOptions one = threads(1), three = threads(3);
    three.tileSize = 4;
    const RenderResult r1 = renderAdaptive(*scene, one, a);
    const RenderResult r3 = renderAdaptive(*scene, three, a);
    RenderOptions crop = threads(2);
    crop.crop = {3, 11, 2, 7};
    const RenderResult rc = renderAdaptive(*scene, crop, a);
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 16; ++x) {
            EXPECT_EQ(r1.film.at(x, y), r3.film.at(x, y));
            if (crop.crop.contains(x, y)) {
                EXPECT_EQ(r1.film.at(x, y), rc.film.at(x, y));
            }
        }
}

TEST(Adaptive, TheMeanConvergesToTheFixedSampleRendersMean) {
    // Unbiased wherever pixels stop: the image mean matches a fixed 256-spp render's within the
    // noise of both.
    auto scene = test::preparedScene(kHalfNoisy);
    RenderOptions fixed = threads(2);
    fixed.spp = 256;
    const RenderResult ref = render(*scene, fixed);
    const RenderResult ad = renderAdaptive(*scene, threads(2), {0.02, 16, 256, 0});
    double a = 0, b = 0;
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 16; ++x) {
            a += ad.film.at(x, y).x;
            b += ref.film.at(x, y).x;
        }
    EXPECT_NEAR(a / b, 1, 0.02);
}

}  // namespace
}  // namespace glint
