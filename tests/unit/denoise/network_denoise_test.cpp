#include "glint/denoise/network_denoise.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "glint/denoise/film_denoise.h"
#include "glint/denoise/unet/unet.h"
#include "glint/denoise/unet/weights.h"
#include "glint/math/rng.h"

namespace glint {
namespace {

TEST(NetworkDenoise, ChoosesOidnsWeightsForTheQualityAndThePasses) {
    auto color = [](DenoiseQuality q, bool albedo, bool normal) {
        return networkChoice(q, albedo, normal).color;
    };
    EXPECT_EQ(color(DenoiseQuality::Balanced, true, true), "rt_hdr_alb_nrm");
    EXPECT_EQ(color(DenoiseQuality::Fast, true, true), "rt_hdr_alb_nrm_small");
    EXPECT_EQ(color(DenoiseQuality::Fast, true, false), "rt_hdr_alb_small");
    EXPECT_EQ(color(DenoiseQuality::Balanced, false, false), "rt_hdr");
    const NetworkChoice high = networkChoice(DenoiseQuality::High, true, true);
    EXPECT_EQ(high.color, "rt_hdr_calb_cnrm_large");
    EXPECT_EQ(high.albedo, "rt_alb_large");
    EXPECT_EQ(high.normal, "rt_nrm_large");
    // No larger network for fewer passes: high is balanced there.
    EXPECT_EQ(networkChoice(DenoiseQuality::High, true, false).color, "rt_hdr_alb");
    EXPECT_TRUE(networkChoice(DenoiseQuality::Balanced, true, true).albedo.empty());

    EXPECT_EQ(denoiseQualityNamed("high"), DenoiseQuality::High);
    EXPECT_EQ(denoiseQualityName(DenoiseQuality::Fast), "fast");
    EXPECT_THROW(denoiseQualityNamed("ultra"), std::invalid_argument);
    EXPECT_EQ(denoiserNamed("oidn"), DenoiserKind::Oidn);
    EXPECT_THROW(denoiserNamed("optix"), std::invalid_argument);
    EXPECT_NE(resolveDenoiser(DenoiserKind::Auto), DenoiserKind::Auto);
    EXPECT_EQ(resolveDenoiser(DenoiserKind::Nlm), DenoiserKind::Nlm);
}

TEST(NetworkDenoise, MissingWeightsSayHowToGetThem) {
    try {
        denoiserNetwork("rt_nothing_of_the_kind");
        FAIL() << "no error";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("no weights 'rt_nothing_of_the_kind'"),
                  std::string::npos);
        EXPECT_NE(std::string(e.what()).find("denoise-weights/fetch.sh"), std::string::npos);
        EXPECT_NE(std::string(e.what()).find("--denoiser nlm"), std::string::npos);
    }
}

TEST(NetworkDenoise, WeightsRegisteredAtRunTimeAreFound) {
    EXPECT_TRUE(denoiserWeights("rt_test_registered").empty());
    registerDenoiserWeights("rt_test_registered", {1, 2, 3});
    const std::span<const uint8_t> first = denoiserWeights("rt_test_registered");
    ASSERT_EQ(first.size(), 3u);
    EXPECT_EQ(first[2], 3);
    registerDenoiserWeights("rt_test_registered", {9});
    EXPECT_EQ(denoiserWeights("rt_test_registered").size(), 1u);
    EXPECT_EQ(first[2], 3);  // the old bytes stay valid
    // Not an archive: the error names it.
    EXPECT_THROW(denoiserNetwork("rt_test_registered"), std::runtime_error);
}

// The tests below run OIDN's own weights: a build without them (denoise-weights/README.md)
// skips them.
#define REQUIRE_WEIGHTS()                                  \
    if (!networkDenoiserAvailable(DenoiseQuality::Fast) || \
        !networkDenoiserAvailable(DenoiseQuality::High))   \
    GTEST_SKIP() << "no OIDN weights in this build"

struct Scene {
    int width, height;
    std::vector<Vec3> color, albedo, normal;
    DenoiseInput input() const {
        DenoiseInput in;
        in.width = width, in.height = height;
        in.color = color.data(), in.albedo = albedo.data(), in.normal = normal.data();
        return in;
    }
};

Scene constant(int width, int height, Vec3 color) {
    const size_t n = static_cast<size_t>(width) * height;
    return {width, height, std::vector<Vec3>(n, color), std::vector<Vec3>(n, Vec3(0.5)),
            std::vector<Vec3>(n, Vec3(0, 0, 1))};
}

TEST(NetworkDenoise, AConstantImageStaysConstantAwayFromItsEdges) {
    REQUIRE_WEIGHTS();
    ThreadPool pool(2);
    for (DenoiseQuality q :
         {DenoiseQuality::Fast, DenoiseQuality::Balanced, DenoiseQuality::High}) {
        const Scene s = constant(80, 64, Vec3(0.5, 0.25, 2.0));
        const NetworkDenoised out = networkDenoise(s.input(), q, pool);
        EXPECT_EQ(out.nonFinite, 0u);
        // The networks pad the image with zeros (as OIDN does): its outermost pixels lean a
        // little; the rest is the constant to a fraction of a percent.
        for (int y = 8; y < 56; ++y)
            for (int x = 8; x < 72; ++x)
                for (int c = 0; c < 3; ++c)
                    ASSERT_NEAR(out.color[static_cast<size_t>(y) * 80 + x][c], s.color[0][c],
                                0.01 * s.color[0][c])
                        << denoiseQualityName(q) << " at " << x << ", " << y;
    }
}

TEST(NetworkDenoise, ScalingTheImageScalesTheResult) {
    REQUIRE_WEIGHTS();
    // The exposure is chosen from the image, so brightness does not change what the network
    // sees: 100 times the light, 100 times the result (to the transfer function's rounding).
    Rng rng(2);
    Scene s = constant(64, 48, Vec3(0));
    for (size_t i = 0; i < s.color.size(); ++i)
        s.color[i] = Vec3(rng.uniform(), rng.uniform(), rng.uniform()) * 0.3;
    ThreadPool pool(2);
    const NetworkDenoised dim = networkDenoise(s.input(), DenoiseQuality::Balanced, pool);
    for (Vec3& c : s.color) c = c * 100.0;
    const NetworkDenoised bright = networkDenoise(s.input(), DenoiseQuality::Balanced, pool);
    for (size_t i = 0; i < dim.color.size(); ++i)
        for (int c = 0; c < 3; ++c)
            ASSERT_NEAR(bright.color[i][c], 100 * dim.color[i][c],
                        1e-3 * (1 + 100 * dim.color[i][c]));
}

TEST(NetworkDenoise, ValuesThatAreNotFiniteAreCountedAndDoNotSpread) {
    REQUIRE_WEIGHTS();
    Scene s = constant(64, 48, Vec3(0.4));
    const double inf = std::numeric_limits<double>::infinity();
    s.color[10 * 64 + 20] = Vec3(std::nan(""), 0.4, 0.4);
    s.color[30 * 64 + 40] = Vec3(inf, inf, inf);
    s.albedo[5 * 64 + 5] = Vec3(-inf, 0.5, 0.5);
    s.normal[40 * 64 + 10] = Vec3(std::nan(""), 0, 1);
    ThreadPool pool(2);
    for (DenoiseQuality q : {DenoiseQuality::Balanced, DenoiseQuality::High}) {
        const NetworkDenoised out = networkDenoise(s.input(), q, pool);
        EXPECT_GE(out.nonFinite, 2u) << denoiseQualityName(q);
        for (const Vec3& c : out.color)
            for (int k = 0; k < 3; ++k) {
                ASSERT_TRUE(std::isfinite(c[k]));
                ASSERT_LT(c[k], 1.0);  // no flood of light from the infinite pixel
            }
    }
    // Through denoiseFilm too, which reports them.
    Film film(64, 48, s.color);
    RenderPasses passes;
    passes.width = 64, passes.height = 48, passes.albedo = s.albedo, passes.normal = s.normal;
    FilmDenoiseReport report;
    denoiseFilm(film, passes, pool, {DenoiserKind::Oidn, DenoiseQuality::Balanced}, &report);
    EXPECT_EQ(report.method, "oidn balanced");
    EXPECT_EQ(report.nonFinite, 4u);
}

TEST(NetworkDenoise, RemovesNoiseAndKeepsTheMean) {
    REQUIRE_WEIGHTS();
    // A lit, textured floor with heavy noise: the network's result is far closer to the clean
    // image than the noisy one, and its mean within a few percent.
    const int w = 96, h = 64;
    Scene clean = constant(w, h, Vec3(0));
    Scene noisy = clean;
    Rng rng(9);
    double errNoisy = 0, errDenoised = 0, meanClean = 0, meanDenoised = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const size_t i = static_cast<size_t>(y) * w + x;
            const Vec3 albedo = ((x / 8 + y / 8) % 2) ? Vec3(0.8, 0.6, 0.3) : Vec3(0.2, 0.3, 0.6);
            const double light = 0.5 + static_cast<double>(x) / w;
            clean.albedo[i] = noisy.albedo[i] = albedo;
            clean.color[i] = albedo * light;
            noisy.color[i] = clean.color[i] * -std::log(1.0 - rng.uniform());  // mean 1
        }
    ThreadPool pool(2);
    const NetworkDenoised out = networkDenoise(noisy.input(), DenoiseQuality::Balanced, pool);
    for (size_t i = 0; i < out.color.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            errNoisy += std::pow(noisy.color[i][c] - clean.color[i][c], 2);
            errDenoised += std::pow(out.color[i][c] - clean.color[i][c], 2);
            meanClean += clean.color[i][c];
            meanDenoised += out.color[i][c];
        }
    EXPECT_LT(errDenoised, errNoisy / 20);
    EXPECT_NEAR(meanDenoised / meanClean, 1.0, 0.05);
}

}  // namespace
}  // namespace glint
