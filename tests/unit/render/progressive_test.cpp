// Rendering to a time budget (render/progressive.h): the passes and their sizes, the average
// weighted by samples, the sample limit, progress that ends at 1, and cancellation.

#include "glint/render/progressive.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>

#include "glint/scene/scene.h"

namespace glint {
namespace {

/// A small path-traced scene: a diffuse sphere under a gradient sky, so that every pass
/// differs.
void buildScene(Scene& scene) {
    scene.width = 24;
    scene.height = 16;
    scene.integrator = "path";
    scene.maxDepth = 3;
    scene.camera = CameraSpec{{0, 1, 5}, {0, 0, 0}, {0, 1, 0}, 40};
    scene.background = Background{{0.1, 0.1, 0.1}, {0.5, 0.7, 1}};
    Material m;
    m.diffuse = Vec3(0.6, 0.5, 0.4);
    scene.primitives.addSphere(Sphere{{0, 0, 0}, 1, {}}, scene.addMaterial(m));
    scene.prepare();
}

RenderOptions oneThread(uint64_t seed = 0) {
    RenderOptions o;
    o.threads = 1;
    o.seed = seed;
    return o;
}

TEST(RenderForTime, PassesDoubleAndAreAveragedByTheirSamples) {
    Scene scene;
    buildScene(scene);
    // Time enough for anything: the sample limit ends it, at 4 + 8 + 16 = 28 samples.
    RenderResult r = renderForTime(scene, oneThread(9), {1e6, 28});
    EXPECT_TRUE(r.complete);
    EXPECT_FALSE(r.stoppedEarly);
    EXPECT_EQ(r.passes, 3);
    EXPECT_EQ(r.samplesPerPixel, 28);
    // The same three passes rendered one by one, averaged by their samples.
    const int spp[3] = {4, 8, 16};
    Film passes[3];
    for (int k = 0; k < 3; ++k) {
        RenderOptions o = oneThread(passSeed(9, k));
        o.spp = spp[k];
        passes[k] = render(scene, o).film;
    }
    for (int y = 0; y < scene.height; ++y)
        for (int x = 0; x < scene.width; ++x) {
            Vec3 expected =
                (passes[0].at(x, y) * 4.0 + passes[1].at(x, y) * 8.0 + passes[2].at(x, y) * 16.0) *
                (1.0 / 28);
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(r.film.at(x, y)[c], expected[c], 1e-12 * (1 + expected[c]));
        }
    // The passes differ: each has its own seed.
    EXPECT_NE(passSeed(9, 0), passSeed(9, 1));
    EXPECT_EQ(passSeed(9, 0), 9u);
    EXPECT_FALSE(passes[0].at(12, 8) == passes[1].at(12, 8));
}

TEST(RenderForTime, TheLastPassIsCutToTheSampleLimit) {
    Scene scene;
    buildScene(scene);
    RenderResult r = renderForTime(scene, oneThread(), {1e6, 13});  // 4 + 8 + 1
    EXPECT_EQ(r.samplesPerPixel, 13);
    EXPECT_EQ(r.passes, 3);
    r = renderForTime(scene, oneThread(), {1e6, 3});  // less than a first pass
    EXPECT_EQ(r.samplesPerPixel, 3);
    EXPECT_EQ(r.passes, 1);
}

TEST(RenderForTime, ATinyBudgetStillRendersOnePass) {
    Scene scene;
    buildScene(scene);
    RenderResult r = renderForTime(scene, oneThread(), {1e-9, 0});
    EXPECT_TRUE(r.complete);
    EXPECT_EQ(r.passes, 1);
    EXPECT_EQ(r.samplesPerPixel, kFirstPassSpp);
    // Every pixel was rendered: none is left at 0 (the sky and the sphere are never black).
    for (int y = 0; y < scene.height; ++y)
        for (int x = 0; x < scene.width; ++x) EXPECT_GT(r.film.at(x, y).y, 0);
}

TEST(RenderForTime, SpendsAboutItsBudget) {
    Scene scene;
    buildScene(scene);
    RenderResult r = renderForTime(scene, oneThread(), {0.3, 0});
    EXPECT_GT(r.passes, 1);
    EXPECT_GT(r.samplesPerPixel, kFirstPassSpp);
    // It never starts a pass it expects to overrun; a loaded machine may still run late.
    EXPECT_GT(r.seconds, 0.1);
    EXPECT_LT(r.seconds, 3.0);
}

TEST(RenderForTime, ProgressRisesToOne) {
    Scene scene;
    buildScene(scene);
    RenderOptions o = oneThread();
    double last = 0;
    int reports = 0;
    bool rising = true;
    o.onProgress = [&](const RenderProgress& p) {
        rising = rising && p.fraction() >= last - 1e-12 && p.fraction() <= 1;
        last = p.fraction();
        ++reports;
    };
    renderForTime(scene, o, {1e6, 28});
    EXPECT_TRUE(rising);
    EXPECT_EQ(last, 1);
    EXPECT_GE(reports, 3);  // at least one per pass
}

TEST(RenderForTime, CancelledAfterAPassKeepsTheFinishedPasses) {
    Scene scene;
    buildScene(scene);
    std::atomic<bool> cancel{false};
    RenderOptions o = oneThread();
    o.cancel = &cancel;
    // The first pass ends at 4 of 28 samples: cancel there, before the second starts.
    o.onProgress = [&](const RenderProgress& p) {
        if (p.fraction() >= 4.0 / 28 - 1e-9) cancel = true;
    };
    RenderResult r = renderForTime(scene, o, {1e6, 28});
    EXPECT_TRUE(r.complete);      // a whole image ...
    EXPECT_TRUE(r.stoppedEarly);  // ... of fewer samples
    EXPECT_EQ(r.samplesPerPixel, 4);
    EXPECT_EQ(r.passes, 1);
    // Cancelled before anything: the first pass's partial image.
    cancel = true;
    o.onProgress = nullptr;
    r = renderForTime(scene, o, {1e6, 28});
    EXPECT_FALSE(r.complete);
    EXPECT_EQ(r.tilesDone, 0);
}

}  // namespace
}  // namespace glint
