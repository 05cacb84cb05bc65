// Frame pieces as OpenEXR files (io/image/exr_piece.h): exact round trips of the sums, the
// header's metadata, what viewers see, malformed, truncated and foreign files, and merging
// rendered pieces into the single render's film.

#include "glint/io/image/exr_piece.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <utility>

#include "glint/core/atomic_file.h"
#include "glint/io/image/exr.h"
#include "glint/math/rng.h"
#include "glint/render/renderer.h"
#include "unit/test_support.h"

namespace glint {
namespace {

using ::testing::HasSubstr;
namespace fs = std::filesystem;

uint64_t bitsOf(double d) {
    uint64_t u;
    std::memcpy(&u, &d, sizeof u);
    return u;
}

PieceInfo info(int width, int height, int spp) {
    PieceInfo p;
    p.width = width;
    p.height = height;
    p.crop = {0, width, 0, height};
    p.tileSize = 4;
    p.spp = spp;
    p.sampleEnd = spp;
    p.seed = 0xfedcba9876543210ULL;
    p.sceneHash = 0x0123456789abcdefULL;
    p.settings = "integrator=path maxdepth=5 camera=my_camera";
    p.version = "9.8.7";
    p.display = {1.5, true, ToneMap::PbrNeutral};
    return p;
}

/// Sums of every kind a double can hold (finite), at the pixels `p` covers.
FilmSums sumsFor(const PieceInfo& p) {
    FilmSums s(p.width, p.height);
    Rng rng(7);
    const double special[] = {0.0,     -0.0, 5e-324, std::numeric_limits<double>::max(),
                              1.0 / 3, -2.5, 1e-300};
    int k = 0;
    for (int y = 0; y < p.height; ++y)
        for (int x = 0; x < p.width; ++x) {
            if (!p.covers(x, y)) continue;
            for (int c = 0; c < 3; ++c) {
                double v = k < 7 ? special[k] : static_cast<double>(rng.uniform()) * 1e3 / 7;
                ++k;
                s.sum(x, y).hi[c] = v;
                s.sum(x, y).lo[c] = -v * 0x1p-60;  // a rounding error's size, and sign
            }
            s.weight(x, y) = p.samples();
        }
    return s;
}

TEST(ExrPiece, RoundTripKeepsEverySumBitForBitAndTheMetadata) {
    PieceInfo p = info(23, 19, 12);
    p.crop = {2, 21, 1, 18};
    p.part = 1;
    p.parts = 3;  // tile rows 1 (4-7) and 4 (16-17 of the crop)
    p.sampleBegin = 4;
    p.sampleEnd = 9;
    const FilmSums sums = sumsFor(p);
    const std::string bytes = encodePiece(p, sums);

    const PieceData d = decodePiece(bytes, "p.exr");
    EXPECT_EQ(d.window, (PixelBounds{2, 21, 4, 18}));
    EXPECT_EQ(d.info.width, 23);
    EXPECT_EQ(d.info.height, 19);
    EXPECT_EQ(d.info.crop, p.crop);
    EXPECT_EQ(d.info.part, 1);
    EXPECT_EQ(d.info.parts, 3);
    EXPECT_EQ(d.info.tileSize, 4);
    EXPECT_EQ(d.info.sampleBegin, 4);
    EXPECT_EQ(d.info.sampleEnd, 9);
    EXPECT_EQ(d.info.spp, 12);
    EXPECT_EQ(d.info.seed, p.seed);
    EXPECT_EQ(d.info.sceneHash, p.sceneHash);
    EXPECT_EQ(d.info.settings, p.settings);
    EXPECT_EQ(d.info.version, "9.8.7");
    EXPECT_EQ(d.info.display.exposure, 1.5);
    EXPECT_TRUE(d.info.display.srgb);
    EXPECT_EQ(d.info.display.toneMap, ToneMap::PbrNeutral);
    int covered = 0;
    for (int y = d.window.y0; y < d.window.y1; ++y)
        for (int x = d.window.x0; x < d.window.x1; ++x) {
            const double w = d.sums.weight(x - d.window.x0, y - d.window.y0);
            const SampleSum& s = d.sums.sum(x - d.window.x0, y - d.window.y0);
            if (!p.covers(x, y)) {
                EXPECT_EQ(w, 0);
                continue;
            }
            ++covered;
            EXPECT_EQ(w, 5);
            for (int c = 0; c < 3; ++c) {
                ASSERT_EQ(bitsOf(s.hi[c]), bitsOf(sums.sum(x, y).hi[c]))
                    << x << "," << y << "," << c;
                ASSERT_EQ(bitsOf(s.lo[c]), bitsOf(sums.sum(x, y).lo[c]))
                    << x << "," << y << "," << c;
            }
        }
    EXPECT_EQ(covered, p.pixelCount());
    EXPECT_EQ(decodePieceInfo(bytes, "p.exr").sceneHash, p.sceneHash);
}

TEST(ExrPiece, AdaptivePiecesKeepTheirSampleCountsAndPassSumsBitForBit) {
    PieceInfo p = info(13, 9, 32);
    p.noiseThreshold = 0.05;
    p.minSpp = 4;
    p.aovs = {.albedo = true, .depth = true};
    p.part = 1;
    p.parts = 2;  // rows 4-7
    FilmSums sums = sumsFor(p);
    sums.keepPasses();
    Rng rng(3);
    for (int y = 0; y < p.height; ++y)
        for (int x = 0; x < p.width; ++x) {
            if (!p.covers(x, y)) continue;
            sums.weight(x, y) = 4 + (x * 7 + y * 3) % 29;  // 4 to 32
            PassSums& ps = sums.passes(x, y);
            ps.squares = Vec3(rng.uniform(), 1.0 / 3, 5e-324);
            ps.albedo = Vec3(rng.uniform(), rng.uniform(), -0.0);
            ps.normal = Vec3(-rng.uniform(), 0.25, 1e300);
            ps.depth = rng.uniform() * 100;
            ps.hits = x % 5;
        }
    const std::string bytes = encodePiece(p, sums);

    const PieceData d = decodePiece(bytes, "p.exr");
    EXPECT_EQ(d.info.noiseThreshold, 0.05);
    EXPECT_EQ(d.info.minSpp, 4);
    EXPECT_EQ(d.info.aovs, p.aovs);
    ASSERT_TRUE(d.sums.hasPasses());
    for (int y = d.window.y0; y < d.window.y1; ++y)
        for (int x = d.window.x0; x < d.window.x1; ++x) {
            const int wx = x - d.window.x0, wy = y - d.window.y0;
            EXPECT_EQ(d.sums.weight(wx, wy), sums.weight(x, y));
            const PassSums &a = d.sums.passes(wx, wy), &b = sums.passes(x, y);
            for (int c = 0; c < 3; ++c) {
                ASSERT_EQ(bitsOf(a.squares[c]), bitsOf(b.squares[c]));
                ASSERT_EQ(bitsOf(a.albedo[c]), bitsOf(b.albedo[c]));
                ASSERT_EQ(bitsOf(a.normal[c]), bitsOf(b.normal[c]));
            }
            ASSERT_EQ(bitsOf(a.depth), bitsOf(b.depth));
            ASSERT_EQ(bitsOf(a.hits), bitsOf(b.hits));
        }
    // A count the header does not allow (below the minimum) is refused by the writer.
    sums.weight(0, 4) = 3;
    EXPECT_THROW(encodePiece(p, sums), RenderError);
    // So are passes the sums do not hold.
    FilmSums bare = sumsFor(info(13, 9, 32));
    EXPECT_THROW(encodePiece(p, bare), RenderError);
}

TEST(ExrPiece, ViewersSeeThePiecesAverageWithItsExposure) {
    PieceInfo p = info(8, 6, 4);
    p.crop = {1, 7, 2, 5};
    p.display.exposure = 1;
    FilmSums sums(8, 6);
    for (int y = 2; y < 5; ++y)
        for (int x = 1; x < 7; ++x) {
            sums.sum(x, y) = SampleSum(Vec3(x, y, 1));
            sums.weight(x, y) = 4;
        }
    const Film film = decodeExr(encodePiece(p, sums), "p.exr");  // R, G, B of the data window
    ASSERT_EQ(film.width(), 6);
    ASSERT_EQ(film.height(), 3);
    EXPECT_EQ(film.at(0, 0), Vec3(0.5, 1, 0.5));  // pixel (1, 2): (1, 2, 1) / 4 * 2
    EXPECT_EQ(film.at(5, 2), Vec3(3, 2, 0.5));    // pixel (6, 4)
}

TEST(ExrPiece, ForeignTruncatedAndDamagedFilesAreErrorsNamingTheFile) {
    auto problem = [](std::string_view bytes) -> std::string {
        try {
            decodePiece(bytes, "x.exr");
        } catch (const PieceError& e) {
            EXPECT_EQ(e.problems().size(), 1u);
            EXPECT_EQ(e.problems()[0].file, "x.exr");
            return e.problems()[0].message;
        }
        return "decoded";
    };
    // An ordinary EXR image is not a piece.
    EXPECT_THAT(problem(encodeExr(Film(4, 3))), HasSubstr("not a Glint frame piece"));
    EXPECT_THAT(problem("P6\n4 4\n255\n"), HasSubstr("not a readable OpenEXR file"));
    EXPECT_THAT(problem(""), HasSubstr("not a readable OpenEXR file"));

    const PieceInfo p = info(16, 12, 2);
    const std::string bytes = encodePiece(p, sumsFor(p));
    ASSERT_EQ(problem(bytes), "decoded");
    // Cut anywhere: an error, never a crash or a piece with missing pixels.
    for (size_t n = 0; n < bytes.size(); n += std::max<size_t>(1, bytes.size() / 97))
        EXPECT_NE(problem(std::string_view(bytes).substr(0, n)), "decoded") << n;
    // Bytes changed in the pixel data (ZIP-compressed): an error, or the same piece (a byte
    // the decompressor ignores); never a crash.
    int errors = 0;
    for (size_t at = bytes.size() / 2; at < bytes.size(); at += 7) {
        std::string bad = bytes;
        bad[at] = static_cast<char>(bad[at] ^ 0x5a);
        errors += problem(bad) != "decoded";
    }
    EXPECT_GT(errors, 0);
}

TEST(ExrPiece, HeadersThatContradictThemselvesAreRefused) {
    PieceInfo p = info(16, 12, 2);
    const FilmSums sums = sumsFor(p);
    auto message = [](const PieceInfo& bad, const FilmSums& s) {
        try {
            decodePieceInfo(encodePiece(bad, s), "x.exr");
        } catch (const PieceError& e) {
            return std::string(e.what());
        }
        return std::string("decoded");
    };
    PieceInfo bad = p;
    bad.spp = 1;  // samples 0:2 of 1
    EXPECT_THAT(message(bad, sums), HasSubstr("glint.samples 0:2 goes beyond glint.spp 1"));
    // A piece whose pixels hold other counts than its header says: refused when read (the
    // header edited in place, "0:2" to "0:1", as a damaged or forged file might be).
    std::string bytes = encodePiece(p, sums);
    const size_t at = bytes.find("0:2");
    ASSERT_NE(at, std::string::npos);
    bytes[at + 2] = '1';
    EXPECT_EQ(decodePieceInfo(bytes, "x.exr").sampleEnd, 1);
    try {
        decodePiece(bytes, "x.exr");
        ADD_FAILURE() << "decoded";
    } catch (const PieceError& e) {
        EXPECT_THAT(e.what(), HasSubstr("pixel (0,0) holds 2 samples where the header says 1"));
    }
    bad = p;
    bad.sampleEnd = 1;
    EXPECT_THROW(encodePiece(bad, sums), RenderError);  // the writer checks too
}

/// The piece fuzzer's inputs (fuzz/corpus/piece, fuzz/regressions/piece) as the harness
/// (fuzz/piece_fuzzer.cpp) takes them: each decodes or is a PieceError; the corpus's own
/// pieces decode, and every cut of them is an error.
TEST(ExrPiece, TheFuzzInputsDecodeOrFailCleanly) {
    int files = 0;
    for (const char* sub : {"corpus/piece", "regressions/piece"}) {
        const fs::path dir = fs::path(GLINT_FUZZ_DIR) / sub;
        if (!fs::exists(dir)) continue;
        for (const auto& e : fs::directory_iterator(dir)) {
            std::ifstream in(e.path(), std::ios::binary);
            const std::string bytes{std::istreambuf_iterator<char>(in), {}};
            ++files;
            try {
                const PieceData d = decodePiece(bytes, e.path().string());
                EXPECT_EQ(d.window, d.info.bounds());
            } catch (const PieceError& err) {
                EXPECT_STREQ(sub, "regressions/piece") << e.path() << ": " << err.what();
            }
            for (size_t n = 0; n < bytes.size(); n += 61)
                EXPECT_THROW(decodePiece(std::string_view(bytes).substr(0, n), "cut"), PieceError);
        }
    }
    EXPECT_GE(files, 2);
}

/// Fuzzed pieces with an attribute claiming more than the file holds: OpenEXR would allocate
/// it before finding the file short (15 s and 2 GB under the fuzzer). In the second, the claim
/// is read where OpenEXR reads it: the channel list ends before its own size says, and OpenEXR
/// goes on from the list's end.
TEST(ExrPiece, AnAttributeLargerThanTheFileIsRefusedBeforeOpenExrReadsIt) {
    const std::pair<const char*, const char*> cases[] = {
        {"attribute-claims-1.8gb.exr", "'glint.part' claims 1818703182 bytes"},
        {"channel-list-ends-before-its-size.exr", "'glint.sceneHash' claims 1660972655 bytes"}};
    for (auto [name, message] : cases) {
        std::ifstream in(fs::path(GLINT_FUZZ_DIR) / "regressions/piece" / name, std::ios::binary);
        const std::string bytes{std::istreambuf_iterator<char>(in), {}};
        ASSERT_FALSE(bytes.empty()) << name;
        try {
            decodePiece(bytes, "p.exr");
            ADD_FAILURE() << name << " decoded";
        } catch (const PieceError& e) {
            EXPECT_THAT(e.what(), ::testing::HasSubstr(message)) << name;
        }
    }
}

class MergePieceFiles : public ::testing::Test {
  protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() / ("glint_merge_" + std::to_string(::getpid()));
        fs::create_directories(dir_);
        test::buildLensScene(scene_, 21, 18, "path");
        whole_ = render(scene_, options());
    }
    void TearDown() override { fs::remove_all(dir_); }

    RenderOptions options() const {
        RenderOptions o;
        o.threads = 2;
        o.tileSize = 4;
        o.spp = 6;
        o.seed = 5;
        o.keepSums = true;
        return o;
    }
    /// Renders the piece `p` (of the scene's frame) and writes it; returns its path.
    std::string write(PieceInfo p, const std::string& name) {
        RenderOptions o = options();
        o.crop = p.crop;
        o.part = p.part;
        o.parts = p.parts;
        o.sampleBegin = p.sampleBegin;
        o.sampleEnd = p.sampleEnd;
        const std::string path = (dir_ / name).string();
        writeFileAtomically(path, encodePiece(p, render(scene_, o).sums));
        return path;
    }
    PieceInfo piece() const {
        PieceInfo p = info(scene_.width, scene_.height, 6);
        p.seed = 5;
        return p;
    }

    fs::path dir_;
    Scene scene_;
    RenderResult whole_;
};

TEST_F(MergePieceFiles, PartsAndCropsGiveTheSingleRenderBitForBit) {
    std::vector<std::string> paths;
    for (int k : {2, 0, 1}) {  // named out of order
        PieceInfo p = piece();
        p.part = k;
        p.parts = 3;
        paths.push_back(write(p, "part" + std::to_string(k) + ".exr"));
    }
    const Film film = mergePieceFiles(paths).sums.resolve();
    int differ = 0;
    for (int y = 0; y < film.height(); ++y)
        for (int x = 0; x < film.width(); ++x) differ += !(film.at(x, y) == whole_.film.at(x, y));
    EXPECT_EQ(differ, 0);
}

TEST_F(MergePieceFiles, SampleRangesGiveTheSameBitsWhateverTheOrderNamed) {
    std::vector<std::string> paths;
    for (auto [a, b] : {std::pair{0, 1}, std::pair{1, 4}, std::pair{4, 6}}) {
        PieceInfo p = piece();
        p.sampleBegin = a;
        p.sampleEnd = b;
        paths.push_back(write(p, "s" + std::to_string(a) + ".exr"));
    }
    const MergedFrame forward = mergePieceFiles(paths);
    const MergedFrame backward = mergePieceFiles({paths[2], paths[0], paths[1]});
    const Film film = forward.sums.resolve();
    int differ = 0;
    for (int y = 0; y < film.height(); ++y)
        for (int x = 0; x < film.width(); ++x) {
            for (int c = 0; c < 3; ++c) {
                ASSERT_EQ(bitsOf(forward.sums.sum(x, y).hi[c]),
                          bitsOf(backward.sums.sum(x, y).hi[c]));
                ASSERT_EQ(bitsOf(forward.sums.sum(x, y).lo[c]),
                          bitsOf(backward.sums.sum(x, y).lo[c]));
            }
            differ += !(film.at(x, y) == whole_.film.at(x, y));
        }
    EXPECT_EQ(differ, 0);  // the exact sums (SampleSum) round to the single render's
}

TEST_F(MergePieceFiles, ProblemsNameTheirFiles) {
    PieceInfo p = piece();
    p.parts = 2;
    const std::string a = write(p, "a.exr");
    const std::string missing = (dir_ / "none.exr").string();
    const std::string foreign = (dir_ / "image.exr").string();
    writeFileAtomically(foreign, encodeExr(Film(3, 3)));
    try {
        mergePieceFiles({a, missing, foreign});
        FAIL() << "merged";
    } catch (const PieceError& e) {
        ASSERT_EQ(e.problems().size(), 2u);
        EXPECT_EQ(e.problems()[0].file, missing);
        EXPECT_THAT(e.problems()[0].message, HasSubstr("cannot read it"));
        EXPECT_EQ(e.problems()[1].file, foreign);
        EXPECT_THAT(e.problems()[1].message, HasSubstr("not a Glint frame piece"));
    }
    try {
        mergePieceFiles({a});
        FAIL() << "merged";
    } catch (const PieceError& e) {
        ASSERT_EQ(e.problems().size(), 1u);
        EXPECT_EQ(e.problems()[0].message,
                  "part 1/2 is missing: no piece covers samples 0:6 of its 168 pixels");
    }
}

}  // namespace
}  // namespace glint
