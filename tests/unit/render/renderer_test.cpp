#include "glint/render/renderer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <utility>
#include <vector>

#include "glint/core/error.h"
#include "glint/core/parallel.h"
#include "glint/math/mat4.h"
#include "glint/render/film/sampler.h"
#include "glint/render/integrators/whitted.h"
#include "unit/test_support.h"

namespace glint {
namespace {

using test::makeMaterial;

/// A mirror floor, a sphere and an ellipsoid, a point and a directional light: shadows and
/// reflections on a small image whose sides are no multiple of the tile sizes used.
void buildScene(Scene& scene) {
    scene.width = 37;
    scene.height = 23;
    scene.maxDepth = 3;
    scene.camera = CameraSpec{{0, 3, 8}, {0, 0.5, 0}, {0, 1, 0}, 45};
    uint32_t floor =
        scene.addMaterial(makeMaterial({0.05, 0.05, 0.05}, {0.5, 0.5, 0.5}, {0.3, 0.3, 0.3}, 20));
    scene.primitives.addTriangle({-5, 0, -5}, {-5, 0, 5}, {5, 0, 5}, nullptr, floor);
    scene.primitives.addTriangle({-5, 0, -5}, {5, 0, 5}, {5, 0, -5}, nullptr, floor);
    uint32_t red =
        scene.addMaterial(makeMaterial({0.1, 0, 0}, {0.8, 0.1, 0.1}, {0.5, 0.5, 0.5}, 50));
    scene.primitives.addSphere(Sphere{{0, 1, 0}, 1, {}}, red);
    uint32_t blue = scene.addMaterial(makeMaterial({0, 0, 0.1}, {0.1, 0.2, 0.8}, {}, 1));
    Mat4 m = Mat4::translate(2, 0.5, 1) * Mat4::rotate(0, 1, 0, 30) * Mat4::scale(1, 0.5, 0.5);
    scene.primitives.addSphere(Sphere{{0, 0, 0}, 1, *Transform::fromMatrix(m)}, blue);
    LightSpec point;
    point.position = {3, 5, 3};
    point.color = {1, 1, 1};
    point.attenuation = {1, 0.1, 0.05};
    scene.lights.push_back(point);
    LightSpec sun;
    sun.kind = LightSpec::Kind::Directional;
    sun.direction = normalize(Vec3{1, 1, -1});
    sun.color = {0.2, 0.2, 0.2};
    scene.lights.push_back(sun);
    scene.prepare();
}

bool sameFilm(const Film& a, const Film& b) {
    if (a.width() != b.width() || a.height() != b.height()) return false;
    for (int y = 0; y < a.height(); ++y)
        for (int x = 0; x < a.width(); ++x)
            if (!(a.at(x, y) == b.at(x, y))) return false;
    return true;
}

RenderOptions withThreads(int threads, int tileSize) {
    RenderOptions o;
    o.threads = threads;
    o.tileSize = tileSize;
    return o;
}

TEST(Renderer, EachPixelIsTheIntegratorAtThePixelCentre) {
    Scene scene;
    buildScene(scene);
    RenderResult r = render(scene, withThreads(1, 16));
    ASSERT_TRUE(r.complete);
    Camera camera(*scene.camera, scene.width, scene.height);
    WhittedIntegrator integrator(scene);
    RayCounts counts;
    int differing = 0;
    for (int y = 0; y < scene.height; ++y)
        for (int x = 0; x < scene.width; ++x) {
            Vec3 expected = integrator.radiance(camera.generateRay(x + 0.5, y + 0.5), 0, counts);
            differing += !(r.film.at(x, y) == expected);
        }
    EXPECT_EQ(differing, 0);
    // The scene really exercises shadows and reflections.
    EXPECT_EQ(r.rays.camera, 37u * 23u);
    EXPECT_GT(r.rays.shadow, 0u);
    EXPECT_GT(r.rays.reflection, 0u);
    EXPECT_EQ(r.rays.total(), counts.total());
}

TEST(Renderer, FilmDoesNotDependOnThreadsOrTileSize) {
    Scene scene;
    buildScene(scene);
    RenderResult reference = render(scene, withThreads(1, 16));
    ASSERT_TRUE(reference.complete);
    for (int threads : {1, 2, 3})
        for (int tile : {1, 5, 16, 64}) {
            SCOPED_TRACE(testing::Message() << threads << " threads, tile " << tile);
            RenderResult r = render(scene, withThreads(threads, tile));
            EXPECT_TRUE(r.complete);
            EXPECT_TRUE(sameFilm(r.film, reference.film));
            EXPECT_EQ(r.rays.total(), reference.rays.total());
        }
}

TEST(Renderer, ProgressEndsWithEveryTileDone) {
    Scene scene;
    buildScene(scene);
    std::vector<RenderProgress> calls;
    RenderOptions o = withThreads(2, 8);
    o.onProgress = [&](const RenderProgress& p) { calls.push_back(p); };
    RenderResult r = render(scene, o);
    EXPECT_TRUE(r.complete);
    ASSERT_FALSE(calls.empty());
    const int tiles = 5 * 3;  // ceil(37 / 8) x ceil(23 / 8)
    EXPECT_EQ(calls.back().tilesTotal, tiles);
    EXPECT_EQ(calls.back().tilesDone, tiles);
    EXPECT_DOUBLE_EQ(calls.back().fraction(), 1.0);
    for (size_t i = 1; i < calls.size(); ++i) {
        EXPECT_GE(calls[i].tilesDone, calls[i - 1].tilesDone);
        EXPECT_EQ(calls[i].tilesTotal, tiles);
    }
}

TEST(Renderer, TileRangesAddUpToTheWholeImage) {
    Scene scene;
    buildScene(scene);
    RenderResult whole = render(scene, withThreads(2, 8));
    ASSERT_TRUE(whole.complete);
    const int tiles = 5 * 3;  // ceil(37 / 8) x ceil(23 / 8)
    Film pieced(scene.width, scene.height);
    uint64_t rays = 0;
    for (auto [first, count] : {std::pair{0, 4}, {4, 1}, {5, 7}, {12, -1}}) {
        SCOPED_TRACE(testing::Message() << "tiles " << first << " + " << count);
        RenderOptions o = withThreads(2, 8);
        o.firstTile = first;
        o.tileCount = count;
        RenderResult r = render(scene, o);
        const int expected = count < 0 ? tiles - first : count;
        EXPECT_TRUE(r.complete);
        EXPECT_EQ(r.tilesTotal, expected);
        EXPECT_EQ(r.tilesDone, expected);
        rays += r.rays.total();
        for (int y = 0; y < scene.height; ++y)
            for (int x = 0; x < scene.width; ++x) {
                const int t = y / 8 * 5 + x / 8;
                if (t >= first && t < first + expected)
                    pieced.at(x, y) = r.film.at(x, y);
                else
                    EXPECT_TRUE(r.film.at(x, y) == Vec3{}) << x << ", " << y;
            }
    }
    EXPECT_TRUE(sameFilm(pieced, whole.film));
    EXPECT_EQ(rays, whole.rays.total());
    // Into a film of the caller's, reused: the same pixels, and none outside the range.
    Film target(scene.width, scene.height);
    target.at(0, 0) = Vec3{7, 7, 7};  // tile 0: not rendered below, so left as it is
    RenderOptions into = withThreads(2, 8);
    into.firstTile = 1;
    into.film = &target;
    RenderResult r = render(scene, into);
    EXPECT_EQ(r.film.width(), 0);
    EXPECT_TRUE(target.at(0, 0) == (Vec3{7, 7, 7}));
    EXPECT_TRUE(target.at(36, 22) == whole.film.at(36, 22));
    EXPECT_TRUE(target.at(8, 0) == whole.film.at(8, 0));
    Film wrong(scene.width + 1, scene.height);
    into.film = &wrong;
    EXPECT_THROW(render(scene, into), RenderError);
    // A range past the last tile renders nothing.
    RenderOptions o = withThreads(1, 8);
    o.firstTile = tiles + 3;
    RenderResult none = render(scene, o);
    EXPECT_EQ(none.tilesTotal, 0);
    EXPECT_EQ(none.rays.total(), 0u);
}

TEST(Renderer, CancelledBeforeStartingIsIncomplete) {
    Scene scene;
    buildScene(scene);
    std::atomic<bool> cancel{true};
    RenderOptions o = withThreads(2, 8);
    o.cancel = &cancel;
    RenderProgress last;
    o.onProgress = [&](const RenderProgress& p) { last = p; };
    RenderResult r = render(scene, o);
    EXPECT_FALSE(r.complete);
    EXPECT_LT(last.tilesDone, last.tilesTotal);
    EXPECT_EQ(r.rays.camera, 0u);
}

TEST(Renderer, OneThreadRendersOnTheCallingThreadAlone) {
    if (test::processThreads() < 0) GTEST_SKIP() << "no /proc/self/task";
    Scene scene;
    buildScene(scene);
    const int before = test::processThreads();
    int during = 0;
    RenderOptions o = withThreads(1, 4);
    o.onProgress = [&](const RenderProgress&) {
        during = std::max(during, test::processThreads());
    };
    EXPECT_TRUE(render(scene, o).complete);
    EXPECT_EQ(during, before);
    ThreadPool one(1);
    o.pool = &one;
    EXPECT_TRUE(render(scene, o).complete);
    EXPECT_EQ(during, before);
    // The check sees threads where there are some: three threads are the caller and two more.
    o.pool = nullptr;
    o.threads = 3;
    EXPECT_TRUE(render(scene, o).complete);
    EXPECT_EQ(during, before + 2);
}

TEST(Renderer, ProgressAndCancelReachTheCallingThreadWithinATile) {
    // One tile, the whole image, at 4096 samples per pixel: seconds of work for one thread.
    // Progress comes between blocks of pixels, so the first report, 100 ms in, can cancel the
    // render long before the tile is done.
    Scene scene;
    buildScene(scene);
    for (int threads : {1, 2}) {
        SCOPED_TRACE(testing::Message() << threads << " threads");
        std::atomic<bool> cancel{false};
        RenderOptions o = withThreads(threads, 64);
        o.spp = 4096;
        o.cancel = &cancel;
        std::vector<RenderProgress> calls;
        o.onProgress = [&](const RenderProgress& p) {
            calls.push_back(p);
            cancel = true;
        };
        RenderResult r = render(scene, o);
        EXPECT_FALSE(r.complete);
        EXPECT_EQ(r.tilesDone, 0);
        ASSERT_GE(calls.size(), 2u);  // one during the tile, one at the end
        EXPECT_EQ(calls.front().tilesDone, 0);
        EXPECT_LT(r.rays.camera, 37u * 23u * 4096u);
    }
}

TEST(Renderer, OnePixelImageSeesWhatIsAtTheImageCentre) {
    // A sphere of angular radius ~0.6 degrees at the centre of a 90 degree view: the ray
    // through the pixel centre hits it, one through a pixel corner would miss by far.
    Scene scene;
    scene.width = scene.height = 1;
    scene.camera = CameraSpec{{0, 0, 0}, {0, 0, -10}, {0, 1, 0}, 90};
    scene.primitives.addSphere(Sphere{{0, 0, -10}, 0.1, {}},
                               scene.addMaterial(makeMaterial({0.25, 0.5, 0.75}, {}, {}, 1)));
    scene.prepare();
    RenderResult r = render(scene, withThreads(1, 16));
    EXPECT_TRUE(r.film.at(0, 0) == Vec3(0.25, 0.5, 0.75));
}

TEST(Renderer, PacketsGiveExactlyTheImageOfOneRayAtATime) {
    // render() traces camera, shadow and mirror rays in packets; the reference below traces
    // every ray alone with WhittedIntegrator::radiance(). They must agree bit for bit.
    Scene scene;
    buildScene(scene);
    for (int spp : {1, 4}) {
        RenderOptions o;
        o.spp = spp;
        o.seed = 7;
        Film packets = render(scene, o).film;

        Film reference(scene.width, scene.height);
        Camera camera(*scene.camera, scene.width, scene.height);
        WhittedIntegrator integrator(scene);
        PixelSampler sampler(spp, 7);
        RayCounts counts;
        for (int y = 0; y < scene.height; ++y)
            for (int x = 0; x < scene.width; ++x) {
                SampleSum sum;  // the film's exact sum of the samples (film.h)
                sampler.forEachSample(x, y, [&](double px, double py) {
                    sum.add(integrator.radiance(camera.generateRay(px, py), 0, counts));
                });
                reference.at(x, y) = pixelValue(sum.value(), spp);
            }
        EXPECT_TRUE(sameFilm(packets, reference)) << spp << " spp";
    }
}

}  // namespace
}  // namespace glint
