// Parts of a frame (RenderOptions::crop, part/parts, sampleBegin/End) and FilmSums: pieces
// rendered apart add up to the single render, bit for bit where each piece renders whole
// pixels, and to within double rounding where pieces split a pixel's samples.

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "glint/render/renderer.h"
#include "glint/render/sampler.h"
#include "unit/test_support.h"

namespace glint {
namespace {

RenderOptions options(int spp) {
    RenderOptions o;
    o.threads = 2;
    o.tileSize = 8;
    o.spp = spp;
    o.seed = 11;
    o.keepSums = true;
    return o;
}

/// Bit-for-bit equality of two films.
void expectSameFilm(const Film& a, const Film& b) {
    ASSERT_EQ(a.width(), b.width());
    ASSERT_EQ(a.height(), b.height());
    int differ = 0;
    for (int y = 0; y < a.height(); ++y)
        for (int x = 0; x < a.width(); ++x) differ += !(a.at(x, y) == b.at(x, y));
    EXPECT_EQ(differ, 0) << "pixels that differ";
}

TEST(FilmPieces, CropPiecesMergeToTheSingleRenderBitForBit) {
    for (const char* integrator : {"path", "whitted"}) {
        Scene scene;
        test::buildLensScene(scene, 29, 21, integrator);
        const RenderResult whole = render(scene, options(6));
        // Four crops of uneven sizes that tile the frame, edges off the tile grid.
        const PixelBounds crops[] = {{0, 13, 0, 9}, {13, 29, 0, 9}, {0, 5, 9, 21}, {5, 29, 9, 21}};
        FilmSums merged(scene.width, scene.height);
        for (const PixelBounds& c : crops) {
            RenderOptions o = options(6);
            o.crop = c;
            RenderResult piece = render(scene, o);
            for (int y = 0; y < scene.height; ++y)
                for (int x = 0; x < scene.width; ++x)
                    ASSERT_EQ(piece.sums.weight(x, y), c.contains(x, y) ? 6 : 0) << x << "," << y;
            merged.add(piece.sums);
        }
        expectSameFilm(merged.resolve(), whole.film);
        expectSameFilm(whole.sums.resolve(), whole.film);
    }
}

TEST(FilmPieces, PartsCoverEveryPixelOnceAndMergeBitForBit) {
    Scene scene;
    test::buildLensScene(scene, 29, 21, "path");
    const RenderResult whole = render(scene, options(4));
    const int parts = 3;  // 21 rows in tile rows of 8: rows 0-7, 8-15, 16-20
    FilmSums merged(scene.width, scene.height);
    std::vector<int> covered(static_cast<size_t>(scene.width * scene.height), 0);
    for (int k = 0; k < parts; ++k) {
        RenderOptions o = options(4);
        o.part = k;
        o.parts = parts;
        RenderResult piece = render(scene, o);
        for (int y = 0; y < scene.height; ++y)
            for (int x = 0; x < scene.width; ++x) {
                const double w = piece.sums.weight(x, y);
                EXPECT_TRUE(w == 0 || w == 4);
                covered[static_cast<size_t>(y * scene.width + x)] += w > 0;
                // Tile row y / 8 belongs to part (y / 8) % 3.
                EXPECT_EQ(w > 0, (y / 8) % parts == k) << x << "," << y;
            }
        merged.add(piece.sums);
    }
    for (int c : covered) ASSERT_EQ(c, 1);
    expectSameFilm(merged.resolve(), whole.film);
}

TEST(FilmPieces, SampleRangesAreTheWholeRendersSamplesAndMergeWithinRounding) {
    Scene scene;
    test::buildLensScene(scene, 29, 21, "path");
    const int spp = 12;
    const RenderResult whole = render(scene, options(spp));
    FilmSums merged(scene.width, scene.height);
    for (auto [begin, end] : {std::pair{0, 5}, std::pair{5, 8}, std::pair{8, 12}}) {
        RenderOptions o = options(spp);
        o.sampleBegin = begin;
        o.sampleEnd = end;
        merged.add(render(scene, o).sums);
    }
    const Film film = merged.resolve();
    double worst = 0;
    for (int y = 0; y < scene.height; ++y)
        for (int x = 0; x < scene.width; ++x) {
            ASSERT_EQ(merged.weight(x, y), spp);
            for (int c = 0; c < 3; ++c) {
                const double a = film.at(x, y)[c], b = whole.film.at(x, y)[c];
                worst = std::max(worst, std::abs(a - b) / std::max(std::abs(b), 1e-300));
            }
        }
    // The samples are the same: only the order of the additions differs (three partial sums
    // added, against one running sum), a few units in the last place of a double.
    EXPECT_LT(worst, 1e-14);

    // A range that is the whole sequence is the whole render itself.
    RenderOptions o = options(spp);
    o.sampleBegin = 0;
    o.sampleEnd = spp;
    expectSameFilm(render(scene, o).film, whole.film);
}

TEST(FilmPieces, TheSamplersRangeIsThatPartOfTheWholeSequence) {
    const PixelSampler sampler(12, 5);
    std::vector<std::pair<double, double>> all, part;
    sampler.forEachSample(3, 7, [&](double x, double y) { all.emplace_back(x, y); });
    sampler.forEachSample(
        3, 7, [&](double x, double y) { part.emplace_back(x, y); }, 5, 9);
    ASSERT_EQ(all.size(), 12u);
    ASSERT_EQ(part.size(), 4u);
    for (size_t i = 0; i < part.size(); ++i) EXPECT_EQ(part[i], all[5 + i]);
}

TEST(FilmPieces, RngAdvanceSkipsExactlyThatManyValues) {
    for (uint64_t n : {0ull, 1ull, 2ull, 7ull, 64ull, 1000ull, 12345ull}) {
        Rng stepped(42, 9), skipped(42, 9);
        for (uint64_t i = 0; i < n; ++i) stepped.next();
        skipped.advance(n);
        for (int i = 0; i < 4; ++i) EXPECT_EQ(skipped.next(), stepped.next()) << n;
    }
}

}  // namespace
}  // namespace glint
