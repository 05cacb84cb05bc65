// Frame pieces (render/film/piece.h): which pixels a piece holds, the merge order, the forms of
// --crop, --part and --samples, and the check that a set of pieces is one frame covered once.

#include "glint/render/film/piece.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

namespace glint {
namespace {

using ::testing::HasSubstr;

/// A piece of a 40x37 frame at 8 samples per pixel, tiles of 8 (5 tile rows, the last 5 high).
PieceInfo frame() {
    PieceInfo p;
    p.width = 40;
    p.height = 37;
    p.crop = {0, 40, 0, 37};
    p.tileSize = 8;
    p.spp = 8;
    p.sampleEnd = 8;
    p.seed = 3;
    p.sceneHash = 0x1234;
    p.settings = "integrator=path maxdepth=5";
    p.version = "1.0.0";
    return p;
}

PieceInfo part(int k, int n) {
    PieceInfo p = frame();
    p.part = k;
    p.parts = n;
    return p;
}

PieceInfo crop(PixelBounds b) {
    PieceInfo p = frame();
    p.crop = b;
    return p;
}

PieceInfo samples(int a, int b) {
    PieceInfo p = frame();
    p.sampleBegin = a;
    p.sampleEnd = b;
    return p;
}

std::vector<std::string> names(size_t n) {
    std::vector<std::string> v;
    for (size_t i = 0; i < n; ++i) {
        std::string name = "p";  // built in steps: GCC 12 misreads "p" + std::to_string(i)
        name += std::to_string(i);
        name += ".exr";
        v.push_back(name);
    }
    return v;
}

std::vector<PieceProblem> check(const std::vector<PieceInfo>& pieces) {
    return checkPieces(pieces, names(pieces.size()));
}

/// Every problem as "file: message", one per line.
std::string text(const std::vector<PieceProblem>& problems) {
    std::string s;
    for (const auto& p : problems) s += (p.file.empty() ? "-" : p.file) + ": " + p.message + "\n";
    return s;
}

TEST(PieceInfo, PartsAreInterleavedTileRows) {
    PieceInfo p = part(1, 2);  // tile rows 1 and 3: pixel rows 8-15 and 24-31
    EXPECT_FALSE(p.covers(0, 7));
    EXPECT_TRUE(p.covers(0, 8));
    EXPECT_TRUE(p.covers(39, 15));
    EXPECT_FALSE(p.covers(0, 16));
    EXPECT_TRUE(p.covers(5, 31));
    EXPECT_FALSE(p.covers(5, 32));
    EXPECT_EQ(p.bounds(), (PixelBounds{0, 40, 8, 32}));
    EXPECT_EQ(p.pixelCount(), 40 * 16);
    EXPECT_EQ(part(0, 2).pixelCount(), 40 * (8 + 8 + 5));
    EXPECT_EQ(part(4, 5).bounds(), (PixelBounds{0, 40, 32, 37}));
    EXPECT_TRUE(part(5, 6).bounds().empty());
    EXPECT_EQ(part(5, 6).pixelCount(), 0);
}

TEST(PieceInfo, PartsOfACropUseTheFramesTileGrid) {
    PieceInfo p = part(0, 2);
    p.crop = {3, 20, 6, 20};  // tile rows 0 (6-7), 1 (8-15), 2 (16-19)
    EXPECT_EQ(p.bounds(), (PixelBounds{3, 20, 6, 20}));
    EXPECT_EQ(p.pixelCount(), 17 * (2 + 4));
    EXPECT_FALSE(p.covers(3, 8));
    EXPECT_FALSE(p.covers(2, 6));
}

TEST(PieceInfo, DescribesWhatItIs) {
    EXPECT_EQ(frame().describe(), "the whole frame");
    EXPECT_EQ(part(2, 4).describe(), "part 2/4");
    PieceInfo p = crop({0, 20, 0, 37});
    p.sampleEnd = 4;
    EXPECT_EQ(p.describe(), "crop 0,20,0,37, samples 0:4");
}

TEST(PieceInfo, MergeOrderIsBySamplesThenPartThenCrop) {
    std::vector<PieceInfo> v = {samples(4, 8), part(1, 2), crop({0, 40, 20, 37}),
                                crop({0, 40, 0, 20}), samples(0, 4)};
    for (PieceInfo& p : v)
        if (p.sampleEnd == 8 && p.sampleBegin == 0) p.sampleEnd = 8;
    std::sort(v.begin(), v.end(), mergesBefore);
    EXPECT_EQ(v[0].sampleEnd, 4);
    EXPECT_EQ(v[1].crop.y0, 0);  // the crops (parts 1) before part 1/2, top one first
    EXPECT_EQ(v[1].crop.y1, 20);
    EXPECT_EQ(v[2].crop.y0, 20);
    EXPECT_EQ(v[3].parts, 2);
    EXPECT_EQ(v[4].sampleBegin, 4);
}

TEST(PieceForms, ParseWhatTheOptionsTake) {
    PixelBounds b;
    EXPECT_EQ(parseCrop("0,320,16,240", b), "");
    EXPECT_EQ(b, (PixelBounds{0, 320, 16, 240}));
    for (const char* bad : {"", "0,320,16", "0,320,16,240,1", "0,,1,2", "-1,3,0,2", "a,b,c,d",
                            "0, 3,0,2", "0,3,0,2,", "1e3,2000,0,2", "0,99999999999,0,2"})
        EXPECT_THAT(parseCrop(bad, b), HasSubstr("expected x0,x1,y0,y1")) << bad;
    EXPECT_THAT(parseCrop("5,5,0,2", b), HasSubstr("is empty"));
    EXPECT_THAT(parseCrop("0,2,9,3", b), HasSubstr("is empty"));

    int k = -1, n = -1;
    EXPECT_EQ(parsePart("3/4", k, n), "");
    EXPECT_EQ(k, 3);
    EXPECT_EQ(n, 4);
    EXPECT_EQ(parsePart("0/65536", k, n), "");
    EXPECT_THAT(parsePart("0/65537", k, n), HasSubstr("N must be 1 to 65536"));
    EXPECT_THAT(parsePart("4/4", k, n), HasSubstr("K must be 0 to N-1"));
    EXPECT_THAT(parsePart("0/0", k, n), HasSubstr("N must be"));
    for (const char* bad : {"3", "3/", "/4", "3/4/5", "-1/4", "1:4"})
        EXPECT_THAT(parsePart(bad, k, n), HasSubstr("expected K/N")) << bad;

    int a = -1, z = -1;
    EXPECT_EQ(parseSampleRange("16:64", a, z), "");
    EXPECT_EQ(a, 16);
    EXPECT_EQ(z, 64);
    EXPECT_THAT(parseSampleRange("8:8", a, z), HasSubstr("A < B"));
    for (const char* bad : {"8", "8:", ":8", "1:2:3", "1-2"})
        EXPECT_THAT(parseSampleRange(bad, a, z), HasSubstr("expected A:B")) << bad;
}

TEST(CheckPieces, CompleteSetsPass) {
    EXPECT_EQ(text(check({part(2, 4), part(0, 4), part(3, 4), part(1, 4)})), "");
    EXPECT_EQ(text(check({crop({0, 13, 0, 37}), crop({13, 40, 0, 20}), crop({13, 40, 20, 37})})),
              "");
    EXPECT_EQ(text(check({samples(5, 8), samples(0, 2), samples(2, 5)})), "");
    // Parts of sample ranges, and a crop at all samples beside them.
    std::vector<PieceInfo> mixed;
    for (auto [a, b] : {std::pair{0, 3}, std::pair{3, 8}})
        for (int k = 0; k < 3; ++k) {
            PieceInfo p = part(k, 3);
            p.crop = {0, 30, 0, 37};
            p.sampleBegin = a;
            p.sampleEnd = b;
            mixed.push_back(p);
        }
    mixed.push_back(crop({30, 40, 0, 37}));
    EXPECT_EQ(text(check(mixed)), "");
    EXPECT_EQ(text(check({frame()})), "");
}

TEST(CheckPieces, NamesAMissingPart) {
    auto problems = check({part(0, 4), part(1, 4), part(3, 4)});
    ASSERT_EQ(problems.size(), 1u) << text(problems);
    EXPECT_EQ(problems[0].file, "");
    EXPECT_EQ(problems[0].message,
              "part 2/4 is missing: no piece covers samples 0:8 of its 320 pixels");
}

TEST(CheckPieces, NamesUncoveredPixelsAndSamples) {
    // The crops leave out columns 13-15 of rows 0-19.
    auto problems = check({crop({0, 13, 0, 37}), crop({16, 40, 0, 20}), crop({13, 40, 20, 37})});
    EXPECT_EQ(text(problems), "-: pixels (13,0)-(15,19): no piece covers samples 0:8\n");

    problems = check({samples(0, 2), samples(5, 8)});
    EXPECT_EQ(text(problems), "-: pixels (0,0)-(39,36): no piece covers samples 2:5\n");
    problems = check({samples(0, 2), samples(2, 6)});
    EXPECT_EQ(text(problems), "-: pixels (0,0)-(39,36): no piece covers samples 6:8\n");
}

TEST(CheckPieces, NamesPiecesGivenTwice) {
    auto problems = check({part(0, 2), part(1, 2), part(1, 2)});
    ASSERT_EQ(problems.size(), 1u) << text(problems);
    EXPECT_EQ(problems[0].file, "p2.exr");
    EXPECT_EQ(problems[0].message, "part 1/2 given twice: p1.exr and p2.exr");
}

TEST(CheckPieces, NamesOverlaps) {
    // Two crops that share columns 10-14.
    auto problems = check({crop({0, 15, 0, 37}), crop({10, 40, 0, 37})});
    EXPECT_EQ(text(problems),
              "p1.exr: samples 0:8 of pixels (10,0)-(14,36) are also in p0.exr (crop "
              "0,15,0,37)\n");
    // Sample ranges that overlap in samples 3 and 4.
    problems = check({samples(0, 5), samples(3, 8)});
    EXPECT_EQ(text(problems),
              "p1.exr: samples 3:5 of pixels (0,0)-(39,36) are also in p0.exr (samples 0:5)\n");
    // A whole frame and a part of it.
    problems = check({frame(), part(1, 3)});
    EXPECT_EQ(text(problems),
              "p1.exr: samples 0:8 of pixels (0,8)-(39,15) and (0,32)-(39,36) are also in p0.exr "
              "(the whole frame)\n");
}

TEST(CheckPieces, PiecesOfOtherFramesAreNamed) {
    PieceInfo other = part(1, 2);
    other.sceneHash = 0x99;
    auto problems = check({part(0, 2), other});
    ASSERT_EQ(problems.size(), 1u);
    EXPECT_EQ(problems[0].file, "p1.exr");
    EXPECT_THAT(problems[0].message,
                HasSubstr("scene hash 0000000000000099, but p0.exr has 0000000000001234"));

    other = part(1, 2);
    other.width = 41;
    EXPECT_THAT(text(check({part(0, 2), other})),
                HasSubstr("p1.exr: a 41x37 frame, but p0.exr is 40x37"));
    other = part(1, 2);
    other.seed = 4;
    EXPECT_THAT(text(check({part(0, 2), other})), HasSubstr("seed 4, but p0.exr has seed 3"));
    other = part(1, 2);
    other.spp = 16;
    other.sampleEnd = 16;
    EXPECT_THAT(text(check({part(0, 2), other})),
                HasSubstr("16 samples per pixel, but p0.exr has 8"));
    other = part(1, 2);
    other.settings = "integrator=path maxdepth=3";
    EXPECT_THAT(text(check({part(0, 2), other})),
                HasSubstr("maxdepth=3, but p0.exr has maxdepth=5"));
    other = part(1, 2);
    other.aovs.albedo = true;
    EXPECT_THAT(text(check({part(0, 2), other})),
                HasSubstr("passes albedo, but p0.exr has no render passes"));
    other = part(1, 2);
    other.noiseThreshold = 0.01;
    other.minSpp = 2;
    EXPECT_THAT(text(check({part(0, 2), other})),
                HasSubstr("adaptive sampling to noise 0.01 from 2 samples, but p0.exr has a "
                          "fixed number of samples per pixel"));
    other = part(1, 2);
    other.version = "1.0.1";
    EXPECT_THAT(text(check({part(0, 2), other})),
                HasSubstr("rendered by glint 1.0.1, but p0.exr by glint 1.0.0"));
}

TEST(CheckPieces, ListsAtMostTheLimitThenHowManyMore) {
    // 39 crops two columns wide, one column apart: each overlaps the next in one column.
    std::vector<PieceInfo> v;
    for (int x = 0; x + 2 <= 40; ++x) v.push_back(crop({x, x + 2, 0, 37}));
    auto problems = checkPieces(v, names(v.size()), 5);
    ASSERT_EQ(problems.size(), 6u) << text(problems);
    EXPECT_EQ(problems[0].message,
              "samples 0:8 of pixels (1,0)-(1,36) are also in p0.exr (crop 0,2,0,37)");
    EXPECT_EQ(problems[5].message, "and 33 more problems");
}

TEST(CheckPieces, SeparateGapsAreNamedApart) {
    auto problems = check({crop({0, 1, 0, 37}), crop({3, 4, 0, 37}), crop({6, 40, 0, 37})});
    EXPECT_EQ(text(problems),
              "-: pixels (1,0)-(2,36) and (4,0)-(5,36): no piece covers samples 0:8\n");
    // Many gaps: their bounding box and count.
    std::vector<PieceInfo> v;
    for (int x = 0; x < 40; x += 3) v.push_back(crop({x, x + 1, 0, 37}));
    EXPECT_EQ(text(check(v)), "-: 962 pixels within (1,0)-(38,36): no piece covers samples 0:8\n");
}

}  // namespace
}  // namespace glint
