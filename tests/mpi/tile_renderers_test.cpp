// glint-mpi's render threads (apps/mpi_tiles.h), without MPI: every tile handed out comes back
// once with the whole render's pixels, and an exception thrown inside a render or while handing
// a tile over is kept as the rank's error and ends every thread. The rank's MPI thread sends that
// error to rank 0, which ends the job naming the rank (tests/mpi/mpi_test.cpp runs that path
// end to end with a rank whose scene does not load).

#include <gtest/gtest.h>

#include <atomic>
#include <deque>
#include <map>
#include <stdexcept>

#include "mpi_tiles.h"
#include "unit/test_support.h"

namespace glint::mpi {
namespace {

constexpr int kSpp = 4;

RenderOptions options() {
    RenderOptions o;
    o.spp = kSpp;
    o.seed = 7;
    return o;
}

/// The frame cut into 8x8 tiles, numbered row by row.
std::deque<Tile> tilesOf(const Scene& scene) {
    std::deque<Tile> tiles;
    for (int y0 = 0; y0 < scene.height; y0 += 8)
        for (int x0 = 0; x0 < scene.width; x0 += 8)
            tiles.push_back(
                {static_cast<int>(tiles.size()),
                 {x0, std::min(x0 + 8, scene.width), y0, std::min(y0 + 8, scene.height)}});
    return tiles;
}

/// The path tracer, which throws once it has been asked for `limit` radiance values.
class FailingIntegrator final : public Integrator {
  public:
    FailingIntegrator(const Scene& scene, long limit)
        : inner_(makeIntegrator(scene, {kSpp})), limit_(limit) {}
    Vec3 li(const Ray& ray, const Hit* hit, PathContext& ctx) const override {
        if (calls_.fetch_add(1) >= limit_) throw std::runtime_error("the integrator gave up");
        return inner_->li(ray, hit, ctx);
    }
    bool usesRandomNumbers() const override { return inner_->usesRandomNumbers(); }

  private:
    std::unique_ptr<Integrator> inner_;
    long limit_;
    mutable std::atomic<long> calls_{0};
};

/// Runs TileRenderers on two threads over `scene`'s tiles until they end; `deliver` is called
/// for each tile rendered (under no lock). Returns the error kept, and counts the tiles taken.
std::string runTiles(const Scene& scene, const RenderOptions& o,
                     const TileRenderers::Deliver& deliver, int& taken,
                     const AdaptiveOptions& adaptive = {.threshold = 0}) {
    Mailbox mailbox;
    std::deque<Tile> tiles = tilesOf(scene);
    taken = 0;
    TileRenderers renderers(
        scene, o, adaptive, 2, mailbox,
        [&](std::unique_lock<std::mutex>&, const std::atomic<bool>&) -> std::optional<Tile> {
            if (tiles.empty()) return std::nullopt;
            Tile t = tiles.front();
            tiles.pop_front();
            ++taken;
            return t;
        },
        deliver);
    renderers.wait();
    std::lock_guard lock(mailbox.mutex);
    EXPECT_TRUE(renderers.finished());
    return renderers.error();
}

TEST(TileRenderers, RenderEveryTileOnceWithTheWholeRendersPixels) {
    Scene scene;
    test::buildLensScene(scene, 27, 19, "path");
    RenderOptions whole = options();
    whole.threads = 1;
    const RenderResult reference = render(scene, whole);
    std::mutex mutex;
    std::map<int, RenderResult> got;
    int taken = 0;
    const std::string error = runTiles(
        scene, options(),
        [&](const Tile& t, RenderResult&& r, double) {
            std::lock_guard lock(mutex);
            EXPECT_TRUE(got.emplace(t.index, std::move(r)).second) << "tile " << t.index;
        },
        taken);
    EXPECT_EQ(error, "");
    const std::deque<Tile> tiles = tilesOf(scene);
    ASSERT_EQ(got.size(), tiles.size());
    EXPECT_EQ(taken, static_cast<int>(tiles.size()));
    int differ = 0;
    for (const Tile& t : tiles) {
        const Film& f = got.at(t.index).film;
        ASSERT_EQ(f.width(), t.bounds.x1 - t.bounds.x0);
        ASSERT_EQ(f.height(), t.bounds.y1 - t.bounds.y0);
        for (int y = t.bounds.y0; y < t.bounds.y1; ++y)
            for (int x = t.bounds.x0; x < t.bounds.x1; ++x)
                differ += !(f.at(x - t.bounds.x0, y - t.bounds.y0) == reference.film.at(x, y));
    }
    EXPECT_EQ(differ, 0);
}

TEST(TileRenderers, AdaptiveTilesWithPassesGiveTheWholeAdaptiveRendersPixelsAndPasses) {
    Scene scene;
    test::buildLensScene(scene, 27, 19, "path");
    const AdaptiveOptions adaptive{.threshold = 0.05, .minSpp = 4, .maxSpp = 64};
    RenderOptions o = options();
    o.spp = adaptive.maxSpp;
    o.aovs = true;
    RenderOptions whole = o;
    whole.threads = 1;
    const RenderResult reference = renderAdaptive(scene, whole, adaptive);
    ASSERT_LT(reference.meanSamplesPerPixel, reference.samplesPerPixel);  // it did adapt
    std::mutex mutex;
    Film film(27, 19);
    RenderPasses aovs(27, 19);
    int taken = 0;
    const std::string error = runTiles(
        scene, o,
        [&](const Tile& t, RenderResult&& r, double) {
            std::lock_guard lock(mutex);
            placeTile(tilePixels(r, true).data(), t.bounds, film, &aovs);
        },
        taken, adaptive);
    EXPECT_EQ(error, "");
    int differ = 0;
    for (int y = 0; y < 19; ++y)
        for (int x = 0; x < 27; ++x) {
            const size_t i = aovs.index(x, y);
            differ += !(film.at(x, y) == reference.film.at(x, y)) ||
                      !(aovs.albedo[i] == reference.aovs.albedo[i]) ||
                      !(aovs.normal[i] == reference.aovs.normal[i]) ||
                      !(aovs.variance[i] == reference.aovs.variance[i]) ||
                      aovs.depth[i] != reference.aovs.depth[i];
        }
    EXPECT_EQ(differ, 0);
}

TEST(TileRenderers, AnExceptionInsideARenderIsKeptAndEndsEveryThread) {
    Scene scene;
    test::buildLensScene(scene, 64, 48, "path");
    // Three tiles' worth of camera samples, then every call throws: mid-frame.
    FailingIntegrator integrator(scene, 3L * 64 * kSpp);
    RenderOptions o = options();
    o.integrator = &integrator;
    std::atomic<int> delivered{0};
    int taken = 0;
    const std::string error = runTiles(
        scene, o, [&](const Tile&, RenderResult&&, double) { delivered.fetch_add(1); }, taken);
    EXPECT_EQ(error, "the integrator gave up");
    const int total = static_cast<int>(tilesOf(scene).size());
    EXPECT_LE(delivered.load(), 3);
    // No thread takes a tile after the failure: at most the one each thread held then.
    EXPECT_LE(taken, delivered.load() + 2);
    EXPECT_LT(taken, total);
}

TEST(TileRenderers, AnExceptionWhileHandingATileOverIsKept) {
    Scene scene;
    test::buildLensScene(scene, 64, 48, "whitted");
    std::atomic<int> delivered{0};
    int taken = 0;
    const std::string error = runTiles(
        scene, options(),
        [&](const Tile&, RenderResult&&, double) {
            if (delivered.fetch_add(1) == 1) throw std::runtime_error("no room for the tile");
        },
        taken);
    EXPECT_EQ(error, "no room for the tile");
    EXPECT_LT(taken, static_cast<int>(tilesOf(scene).size()));
}

}  // namespace
}  // namespace glint::mpi
