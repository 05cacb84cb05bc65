// Render passes (AOVs): what the integrators report per sample, how the renderer averages them,
// how pieces add up, and their round trip through OpenEXR layers.

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "glint/io/image/exr.h"
#include "glint/render/progressive.h"
#include "glint/render/renderer.h"
#include "unit/test_support.h"

namespace glint {
namespace {

/// A camera looking down -z at a wall 4 units away (z = -4) that fills the left half of the
/// image: diffuse (0.5, 0.25, 0.1) under a sky light; the right half sees the sky.
const char* kWall =
    "size 16 8\n"
    "integrator path\n"
    "camera 0 0 0  0 0 -1  0 1 0  90\n"
    "background 1 1 1\n"
    "ambient 0 0 0\n"
    "diffuse 0.5 0.25 0.1\n"
    "vertex -100 -100 -4\nvertex 0 -100 -4\nvertex 0 100 -4\nvertex -100 100 -4\n"
    "tri 0 1 2\ntri 0 2 3\n";

RenderOptions passesAt(int spp, int threads = 1) {
    RenderOptions o;
    o.spp = spp;
    o.threads = threads;
    o.aovs = true;
    return o;
}

TEST(Aovs, ThePathTracerReportsTheFirstSurfacesAlbedoNormalAndDepth) {
    auto scene = test::preparedScene(kWall);
    RenderResult r = render(*scene, passesAt(4));
    const RenderPasses& p = r.aovs;
    ASSERT_EQ(p.width, 16);
    ASSERT_EQ(p.albedo.size(), 16u * 8);
    // A wall pixel away from the edge: the wall's colour, its normal (+z, towards the camera),
    // and the distance along the pixel's rays (at least 4, the wall's distance straight ahead).
    const size_t wall = p.index(3, 4), sky = p.index(12, 4);
    EXPECT_NEAR(p.albedo[wall].x, 0.5, 1e-12);
    EXPECT_NEAR(p.albedo[wall].y, 0.25, 1e-12);
    EXPECT_NEAR(p.albedo[wall].z, 0.1, 1e-12);
    EXPECT_NEAR(p.normal[wall].z, 1, 1e-9);
    EXPECT_GT(p.depth[wall], 4);
    EXPECT_LT(p.depth[wall], 4 * std::sqrt(3.0));
    // The sky: no surface.
    EXPECT_EQ(p.albedo[sky], Vec3(0));
    EXPECT_EQ(p.normal[sky], Vec3(0));
    EXPECT_EQ(p.depth[sky], 0);
    // The sky is seen exactly (white): no variance; the wall's lighting is sampled: some.
    EXPECT_EQ(p.variance[sky], Vec3(0));
    EXPECT_GT(p.variance[wall].x, 0);
}

TEST(Aovs, PassesFollowPerfectMirrorsToWhatTheyShow) {
    // A mirror (specular 0.8, no diffuse) fills the view; it reflects the diffuse wall behind
    // the camera.
    auto scene = test::preparedScene(
        "size 8 8\nintegrator path\ncamera 0 0 0  0 0 -1  0 1 0  40\nbackground 1 1 1\n"
        "ambient 0 0 0\nspecular 0.8 0.8 0.8\n"
        "vertex -100 -100 -4\nvertex 100 -100 -4\nvertex 100 100 -4\nvertex -100 100 -4\n"
        "tri 0 1 2\ntri 0 2 3\n"
        "specular 0 0 0\ndiffuse 0.2 0.6 0.4\n"
        "vertex -100 -100 4\nvertex 100 -100 4\nvertex 100 100 4\nvertex -100 100 4\n"
        "tri 4 6 5\ntri 4 7 6\n");
    RenderResult r = render(*scene, passesAt(4));
    const size_t i = r.aovs.index(4, 4);
    // The wall's albedo through the mirror's tint, the wall's normal (-z, facing the mirror);
    // the depth is the mirror's, the first surface hit.
    EXPECT_NEAR(r.aovs.albedo[i].x, 0.8 * 0.2, 1e-9);
    EXPECT_NEAR(r.aovs.albedo[i].y, 0.8 * 0.6, 1e-9);
    EXPECT_NEAR(r.aovs.normal[i].z, -1, 1e-9);
    EXPECT_GT(r.aovs.depth[i], 4);
    EXPECT_LT(r.aovs.depth[i], 4.3);
}

TEST(Aovs, PassesFollowGlassAlongItsMoreLikelyBranchWhateverThePathChose) {
    // A pane of glass (a thin box, index 1.5) in front of a diffuse wall: at normal incidence
    // 4% of the light reflects (to the sky behind the camera) and 96% passes. The path picks
    // one at random per sample; the passes always go through, to the wall, so the albedo is
    // the wall's at every sample: no variance (before, 4% of the samples gave the sky's 0).
    auto scene = test::preparedScene(
        "size 8 8\nintegrator path\ncamera 0 0 0  0 0 -1  0 1 0  30\nbackground 1 1 1\n"
        "ambient 0 0 0\ntransmission 1 1 1\nior 1.5\nbox -10 -10 -2.1  10 10 -2\n"
        "transmission 0 0 0\ndiffuse 0.2 0.6 0.4\n"
        "vertex -100 -100 -4\nvertex 100 -100 -4\nvertex 100 100 -4\nvertex -100 100 -4\n"
        "tri 0 1 2\ntri 0 2 3\n");
    const RenderResult r = render(*scene, passesAt(256));
    for (const size_t i : {r.aovs.index(4, 4), r.aovs.index(1, 6)}) {
        // Through both faces: (1/1.5)^2 in, capped at 1 out (the passes' tint is at most 1).
        EXPECT_NEAR(r.aovs.albedo[i].y, 0.6 / (1.5 * 1.5), 1e-9);
        // (Zero but for rounding; the path's own choice would give about 1e-5.)
        EXPECT_LT(maxComponent(r.aovs.albedoVariance[i]), 1e-15);
        EXPECT_NEAR(r.aovs.normal[i].z, 1, 1e-9);
    }
    // The image itself is the path's: some of its samples saw the reflection.
    EXPECT_GT(r.aovs.variance[r.aovs.index(4, 4)].y, 0);
}

TEST(Aovs, VarianceIsTheSampleVarianceOfThePixelsMean) {
    // Two samples 1 and 3: mean 2, sample variance 2, the mean's 1. Their albedos 0.2 and 0.6
    // (one sample saw one surface, the other another): mean 0.4, the mean's variance 0.04.
    PassSums p;
    SamplePasses s;
    s.albedo = Vec3(0.2, 0.5, 0.5);
    p.addSample(Vec3(1), s);
    s.albedo = Vec3(0.6, 0.5, 0.5);
    p.addSample(Vec3(3), s);
    RenderPasses out(1, 1);
    resolvePassesAt(Vec3(4), 2, p, out, 0);
    EXPECT_NEAR(out.variance[0].x, 1, 1e-12);
    EXPECT_NEAR(out.albedo[0].x, 0.4, 1e-12);
    EXPECT_NEAR(out.albedoVariance[0].x, 0.04, 1e-12);
    EXPECT_EQ(out.albedoVariance[0].y, 0);  // the same albedo: none (never negative)
    // One sample: unknown, 0.
    PassSums one;
    one.addSample(Vec3(5), s);
    resolvePassesAt(Vec3(5), 1, one, out, 0);
    EXPECT_EQ(out.variance[0], Vec3(0));
    EXPECT_EQ(out.albedoVariance[0], Vec3(0));
}

TEST(Aovs, PassesDoNotChangeTheImageAndDoNotDependOnThreads) {
    auto scene = test::preparedScene(kWall);
    RenderOptions plain;
    plain.spp = 8;
    plain.threads = 1;
    const RenderResult a = render(*scene, plain);
    const RenderResult b = render(*scene, passesAt(8, 1));
    const RenderResult c = render(*scene, passesAt(8, 3));
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 16; ++x) {
            EXPECT_EQ(a.film.at(x, y), b.film.at(x, y));
            EXPECT_EQ(b.film.at(x, y), c.film.at(x, y));
        }
    EXPECT_EQ(b.aovs.albedo, c.aovs.albedo);
    EXPECT_EQ(b.aovs.variance, c.aovs.variance);
    EXPECT_EQ(b.aovs.depth, c.aovs.depth);
}

TEST(Aovs, SampleRangePiecesAddUpToTheWholeRendersPasses) {
    auto scene = test::preparedScene(kWall);
    RenderOptions whole = passesAt(8);
    whole.keepSums = true;
    const RenderResult all = render(*scene, whole);
    FilmSums merged(16, 8);
    merged.keepPasses();
    for (auto [begin, end] : {std::pair{0, 3}, std::pair{3, 8}}) {
        RenderOptions o = whole;
        o.sampleBegin = begin;
        o.sampleEnd = end;
        merged.add(render(*scene, o).sums);
    }
    const RenderPasses p = merged.resolvePasses();
    for (size_t i = 0; i < p.albedo.size(); ++i) {
        EXPECT_NEAR(p.variance[i].x, all.aovs.variance[i].x, 1e-9 * (1 + all.aovs.variance[i].x));
        EXPECT_NEAR(p.albedo[i].y, all.aovs.albedo[i].y, 1e-12);
        EXPECT_NEAR(p.depth[i], all.aovs.depth[i], 1e-9);
    }
}

TEST(Aovs, RendersToATimeBudgetHavePassesToo) {
    auto scene = test::preparedScene(kWall);
    RenderOptions o = passesAt(1);
    const RenderResult r = renderForTime(*scene, o, {10, 8});
    ASSERT_EQ(r.samplesPerPixel, 8);
    ASSERT_FALSE(r.aovs.empty());
    EXPECT_NEAR(r.aovs.albedo[r.aovs.index(3, 4)].x, 0.5, 1e-12);
    EXPECT_GT(r.aovs.variance[r.aovs.index(3, 4)].x, 0);
}

TEST(Aovs, PassesRoundTripThroughOpenExrLayers) {
    auto scene = test::preparedScene(kWall);
    const RenderResult r = render(*scene, passesAt(4));
    const ExrLayers back =
        decodeExrLayers(encodeExr(r.film, 2, &r.aovs, AovSelection::all()), "mem.exr");
    ASSERT_TRUE(back.found.albedo && back.found.normal && back.found.depth && back.found.variance);
    ASSERT_EQ(back.aovs.albedoVariance.size(), r.aovs.albedoVariance.size());
    for (size_t i = 0; i < r.aovs.albedo.size(); ++i) {
        const int x = static_cast<int>(i % 16), y = static_cast<int>(i / 16);
        // Each value as the float it was written as.
        auto asFloat = [](double v) { return static_cast<double>(static_cast<float>(v)); };
        EXPECT_EQ(back.color.at(x, y).x, asFloat(2 * r.film.at(x, y).x));
        EXPECT_EQ(back.aovs.albedo[i].z, asFloat(r.aovs.albedo[i].z));
        EXPECT_EQ(back.aovs.normal[i].z, asFloat(r.aovs.normal[i].z));
        EXPECT_EQ(back.aovs.depth[i], asFloat(r.aovs.depth[i]));
        // The variance of the colour times 2: times 4.
        EXPECT_EQ(back.aovs.variance[i].y, asFloat(4 * r.aovs.variance[i].y));
        // The albedo's variance, with the albedo and the variance: not scaled.
        EXPECT_EQ(back.aovs.albedoVariance[i].x, asFloat(r.aovs.albedoVariance[i].x));
    }
    // Only the passes asked for are written.
    AovSelection some;
    some.depth = true;
    const ExrLayers depthOnly = decodeExrLayers(encodeExr(r.film, 1, &r.aovs, some), "d.exr");
    EXPECT_TRUE(depthOnly.found.depth);
    EXPECT_FALSE(depthOnly.found.albedo || depthOnly.found.normal || depthOnly.found.variance);
    EXPECT_TRUE(depthOnly.aovs.albedoVariance.empty());
    // The variance alone: the albedo's is written only beside the albedo.
    AovSelection variance;
    variance.variance = true;
    EXPECT_TRUE(decodeExrLayers(encodeExr(r.film, 1, &r.aovs, variance), "v.exr")
                    .aovs.albedoVariance.empty());
    // A file without passes has none.
    EXPECT_FALSE(decodeExrLayers(encodeExr(r.film), "plain.exr").found.any());
}

}  // namespace
}  // namespace glint
