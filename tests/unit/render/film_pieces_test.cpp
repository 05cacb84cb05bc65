// Parts of a frame (RenderOptions::crop, part/parts, sampleBegin/End) and FilmSums: pieces
// rendered apart add up to the single render bit for bit, whether each piece renders whole
// pixels or a range of every pixel's samples (SampleSum keeps the sums exact).

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "glint/render/renderer.h"
#include "glint/render/film/sampler.h"
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

TEST(FilmPieces, SampleRangesAreTheWholeRendersSamplesAndMergeBitForBit) {
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
    for (int y = 0; y < scene.height; ++y)
        for (int x = 0; x < scene.width; ++x) ASSERT_EQ(merged.weight(x, y), spp);
    // The samples are the same, added in another grouping (three partial sums against one
    // running sum): the exact sums round to the same doubles.
    expectSameFilm(merged.resolve(), whole.film);

    // A range that is the whole sequence is the whole render itself.
    RenderOptions o = options(spp);
    o.sampleBegin = 0;
    o.sampleEnd = spp;
    expectSameFilm(render(scene, o).film, whole.film);
}

TEST(FilmPieces, SampleSumsDoNotDependOnHowTheSamplesAreGrouped) {
    // Six samples of 0.4, a flat colour on an 8-bit level's edge (255 x 0.4 = 102): a plain
    // running sum and partial sums of 2 + 4 round differently, and floor(255 c) of their
    // averages are 101 and 102. The exact sums agree.
    double running = 0, first = 0, second = 0;
    SampleSum one, a, b;
    for (int k = 0; k < 6; ++k) {
        running += 0.4;
        (k < 2 ? first : second) += 0.4;
        one.add(Vec3(0.4));
        (k < 2 ? a : b).add(Vec3(0.4));
    }
    ASSERT_NE(running, first + second);  // what the plain sums did
    a.add(b);
    EXPECT_EQ(one.value(), a.value());
    EXPECT_EQ(toByte(one.value().x * (1.0 / 6)), toByte(a.value().x * (1.0 / 6)));

    // Values far apart in magnitude, in every grouping of three ranges.
    Rng rng(11);
    std::vector<Vec3> v;
    for (int k = 0; k < 64; ++k) {
        const double m = std::exp2(static_cast<int>(rng.uniform() * 40) - 20);
        v.push_back(Vec3(rng.uniform() * m, rng.uniform() * 1e3, rng.uniform() * 1e-3));
    }
    SampleSum whole;
    for (const Vec3& x : v) whole.add(x);
    for (size_t i = 1; i < v.size(); i += 7)
        for (size_t j = i; j < v.size(); j += 5) {
            SampleSum p0, p1, p2;
            for (size_t k = 0; k < v.size(); ++k) (k < i ? p0 : k < j ? p1 : p2).add(v[k]);
            p0.add(p1);
            p0.add(p2);
            ASSERT_EQ(p0.value(), whole.value()) << i << "," << j;
        }

    // Infinite and NaN samples keep the plain sum's result (not a NaN error term).
    SampleSum inf;
    inf.add(Vec3(1, 1, 1));
    inf.add(Vec3(std::numeric_limits<double>::infinity(), 2, 2));
    inf.add(Vec3(3, 3, 3));
    EXPECT_EQ(inf.value().x, std::numeric_limits<double>::infinity());
    EXPECT_EQ(inf.value().y, 6);
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
