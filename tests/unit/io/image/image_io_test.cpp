#include "glint/io/image/image_io.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <unistd.h>

#include <bit>
#include <csignal>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <set>

#include "glint/core/error.h"
#include "glint/core/atomic_file.h"
#include "unit/test_support.h"

#if defined(__SANITIZE_ADDRESS__)
#define GLINT_TEST_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define GLINT_TEST_ASAN 1
#endif
#endif

namespace glint {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;
namespace fs = std::filesystem;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// A 3 x 2 film whose pixels all differ, with values inside and outside [0, 1].
Film testFilm() {
    Film f(3, 2);
    f.at(0, 0) = {0.7, 1.0, 0.999};
    f.at(1, 0) = {-0.5, 1.5, 0.5};
    f.at(2, 0) = {0.25, 0.0, 2.0};
    f.at(0, 1) = {0.1, 0.2, 0.3};
    f.at(1, 1) = {kNaN, 0.9, 1e9};
    f.at(2, 1) = {0.004, 0.996, -1e9};
    return f;
}

std::string readBytes(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void writeBytes(const fs::path& p, const std::string& bytes) {
    std::ofstream(p, std::ios::binary) << bytes;
}

void appendFloat(std::string& out, float f, bool bigEndian) {
    uint32_t bits = std::bit_cast<uint32_t>(f);
    for (int i = 0; i < 4; ++i) {
        int shift = bigEndian ? 24 - 8 * i : 8 * i;
        out.push_back(static_cast<char>((bits >> shift) & 0xff));
    }
}

/// Each test gets its own empty directory, removed afterwards.
class ImageIo : public test::TempDirTest {};

void expectSameImage(const Image8& a, const Image8& b) {
    EXPECT_EQ(a.width, b.width);
    EXPECT_EQ(a.height, b.height);
    EXPECT_EQ(a.channels, b.channels);
    EXPECT_EQ(a.data, b.data);
}

// ---- 8-bit conversion -------------------------------------------------------------------

TEST(ImageToByte, ClampsThenFloorsTwoFiftyFiveTimesTheValue) {
    EXPECT_EQ(toByte(0.7), 178);  // 178.5 floors, as in the official images
    EXPECT_EQ(toByte(0.5), 127);  // 127.5: rounding would give 128
    EXPECT_EQ(toByte(0.999), 254);
    EXPECT_EQ(toByte(1.0), 255);
    EXPECT_EQ(toByte(0.0), 0);
    EXPECT_EQ(toByte(3.0), 255);
    EXPECT_EQ(toByte(std::numeric_limits<double>::infinity()), 255);
    EXPECT_EQ(toByte(-0.2), 0);
    EXPECT_EQ(toByte(-std::numeric_limits<double>::infinity()), 0);
    EXPECT_EQ(toByte(kNaN), 0);
}

TEST(ImageToByte, ToImage8ConvertsEveryChannelRowZeroFirst) {
    Image8 img = toImage8(testFilm());
    EXPECT_EQ(img.width, 3);
    EXPECT_EQ(img.height, 2);
    EXPECT_EQ(img.channels, 3);
    ASSERT_EQ(img.data.size(), 18u);
    EXPECT_THAT(std::vector<uint8_t>(img.data.begin(), img.data.begin() + 9),
                ElementsAre(178, 255, 254, 0, 255, 127, 63, 0, 255));
    EXPECT_THAT(std::vector<uint8_t>(img.data.begin() + 9, img.data.end()),
                ElementsAre(25, 51, 76, 0, 229, 255, 1, 253, 0));
    EXPECT_EQ(img.at(1, 1, 1), 229);
}

// ---- formats ----------------------------------------------------------------------------

TEST(ImageFormatFor, RecognisesExtensionsIgnoringCase) {
    EXPECT_EQ(imageFormatFor("a.png"), ImageFormat::Png);
    EXPECT_EQ(imageFormatFor("out/A.PNG"), ImageFormat::Png);
    EXPECT_EQ(imageFormatFor("x.Ppm"), ImageFormat::Ppm);
    EXPECT_EQ(imageFormatFor("y.pfm"), ImageFormat::Pfm);
    EXPECT_EQ(imageFormatFor("a.b.PfM"), ImageFormat::Pfm);
}

TEST(ImageFormatFor, RejectsUnknownOrMissingExtensions) {
    EXPECT_EQ(imageFormatFor("a.jpg"), std::nullopt);
    EXPECT_EQ(imageFormatFor("png"), std::nullopt);
    EXPECT_EQ(imageFormatFor("image"), std::nullopt);
    EXPECT_EQ(imageFormatFor("image."), std::nullopt);
    EXPECT_EQ(imageFormatFor(""), std::nullopt);
    EXPECT_EQ(imageFormatFor("a.pngx"), std::nullopt);
}

TEST(ImageFormatFor, ADotInADirectoryNameIsNotAnExtension) {
    EXPECT_EQ(imageFormatFor("renders.png/image"), std::nullopt);
    EXPECT_EQ(imageFormatFor("./image"), std::nullopt);
    EXPECT_EQ(imageFormatFor("v1.2/image.ppm"), ImageFormat::Ppm);
}

TEST(ImageEncode, PpmIsABinaryP6WithTheClampedBytes) {
    std::string ppm = encodeImage(testFilm(), ImageFormat::Ppm);
    const std::string header = "P6\n3 2\n255\n";
    ASSERT_EQ(ppm.size(), header.size() + 18);
    EXPECT_EQ(ppm.substr(0, header.size()), header);
    Image8 img = toImage8(testFilm());
    EXPECT_EQ(ppm.substr(header.size()), std::string(img.data.begin(), img.data.end()));
}

TEST(ImageEncode, PfmIsLittleEndianWithRowsFromTheBottomUp) {
    Film f = testFilm();
    std::string pfm = encodeImage(f, ImageFormat::Pfm);
    const std::string header = "PF\n3 2\n-1.0\n";
    ASSERT_EQ(pfm.size(), header.size() + 3 * 2 * 12);
    EXPECT_EQ(pfm.substr(0, header.size()), header);
    std::string firstPixel;  // bottom-left: (0, 1)
    for (int c = 0; c < 3; ++c) appendFloat(firstPixel, static_cast<float>(f.at(0, 1)[c]), false);
    EXPECT_EQ(pfm.substr(header.size(), 12), firstPixel);
}

// ---- round trips ------------------------------------------------------------------------

TEST_F(ImageIo, PngRoundTripGivesTheClampedBytes) {
    Film f = testFilm();
    writeImage(path("a.png"), f);
    expectSameImage(readImage8(path("a.png")), toImage8(f));
    expectSameImage(readImage8(path("a.png"), 3), toImage8(f));
}

TEST_F(ImageIo, PpmRoundTripGivesTheClampedBytes) {
    Film f = testFilm();
    writeImage(path("a.ppm"), f);
    expectSameImage(readImage8(path("a.ppm")), toImage8(f));
}

TEST_F(ImageIo, LargerPngRoundTripIsExact) {
    Film f(37, 23);
    for (int y = 0; y < f.height(); ++y)
        for (int x = 0; x < f.width(); ++x) f.at(x, y) = {x / 36.0, y / 22.0, (x * y % 7) / 6.0};
    writeImage(path("b.PNG"), f);
    expectSameImage(readImage8(path("b.PNG")), toImage8(f));
}

TEST_F(ImageIo, PfmRoundTripIsBitExactInFloat) {
    Film f(3, 2);
    f.at(0, 0) = {1.5, -2.25, 1e-3};
    f.at(1, 0) = {1e30, -1e-30, 0.1};
    f.at(2, 0) = {0, -0.0, 12345.678};
    f.at(0, 1) = {0.7, 0.999, 100};
    f.at(1, 1) = {-7, 3.0e38, 1e-40};  // the last one is a float denormal
    f.at(2, 1) = {0.5, 0.25, 0.125};
    writeImage(path("a.pfm"), f);
    Film g = readPfm(path("a.pfm"));
    ASSERT_EQ(g.width(), 3);
    ASSERT_EQ(g.height(), 2);
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 3; ++x)
            for (int c = 0; c < 3; ++c) {
                float want = static_cast<float>(f.at(x, y)[c]);
                float got = static_cast<float>(g.at(x, y)[c]);
                EXPECT_EQ(std::bit_cast<uint32_t>(got), std::bit_cast<uint32_t>(want))
                    << x << "," << y << "," << c;
                EXPECT_EQ(g.at(x, y)[c], static_cast<double>(want));
            }
}

TEST_F(ImageIo, ReadsBigEndianPfmWithPositiveScale) {
    std::string bytes = "PF\n2 2\n1.0\n";
    // Rows from the bottom: bottom-left, bottom-right, then top-left, top-right.
    const float values[4][3] = {{1, 2, 3}, {4, 5, 6}, {-1.5f, 0.25f, 7e20f}, {0, 8, 9}};
    for (const auto& px : values)
        for (float v : px) appendFloat(bytes, v, true);
    writeBytes(dir_ / "be.pfm", bytes);
    Film f = readPfm(path("be.pfm"));
    ASSERT_EQ(f.width(), 2);
    ASSERT_EQ(f.height(), 2);
    EXPECT_EQ(f.at(0, 1), Vec3(1, 2, 3));
    EXPECT_EQ(f.at(1, 1), Vec3(4, 5, 6));
    EXPECT_EQ(f.at(0, 0), Vec3(-1.5, 0.25, static_cast<double>(7e20f)));
    EXPECT_EQ(f.at(1, 0), Vec3(0, 8, 9));
}

TEST_F(ImageIo, ReadsGreyPfmIntoAllThreeChannels) {
    std::string bytes = "Pf\n3 1\n-1.0\n";
    for (float v : {0.5f, -2.0f, 1e10f}) appendFloat(bytes, v, false);
    writeBytes(dir_ / "grey.pfm", bytes);
    Film f = readPfm(path("grey.pfm"));
    ASSERT_EQ(f.width(), 3);
    ASSERT_EQ(f.height(), 1);
    EXPECT_EQ(f.at(0, 0), Vec3(0.5));
    EXPECT_EQ(f.at(1, 0), Vec3(-2.0));
    EXPECT_EQ(f.at(2, 0), Vec3(static_cast<double>(1e10f)));
}

TEST_F(ImageIo, MalformedOrTruncatedPfmIsARenderError) {
    writeBytes(dir_ / "p6.pfm", "P6\n1 1\n255\nabc");
    EXPECT_THROW(readPfm(path("p6.pfm")), RenderError);
    std::string truncated = "PF\n2 1\n-1.0\n";
    appendFloat(truncated, 1, false);
    writeBytes(dir_ / "short.pfm", truncated);
    EXPECT_THROW(readPfm(path("short.pfm")), RenderError);
    writeBytes(dir_ / "zero.pfm", "PF\n0 1\n-1.0\n");
    EXPECT_THROW(readPfm(path("zero.pfm")), RenderError);
    EXPECT_THROW(readPfm(path("missing.pfm")), RenderError);
}

TEST_F(ImageIo, PfmHeaderClaimingAHugeImageIsRejectedWithoutAllocatingIt) {
#ifdef GLINT_TEST_ASAN
    GTEST_SKIP() << "an address-space limit conflicts with the sanitizer's shadow memory";
#else
    // 65536 x 65536 RGB floats would be 48 GiB, and the file holds no pixel data at all: the
    // reader must see that it is truncated. The address space is limited to 2 GiB more than
    // now, so a reader that trusts the header fails with bad_alloc instead of hogging memory.
    writeBytes(dir_ / "huge.pfm", "PF\n65536 65536\n-1.0\n");
    long pages = 0;
    std::ifstream("/proc/self/statm") >> pages;
    ASSERT_GT(pages, 0);
    rlimit old{};
    ASSERT_EQ(::getrlimit(RLIMIT_AS, &old), 0);
    rlimit limited = old;
    limited.rlim_cur = static_cast<rlim_t>(pages) * static_cast<rlim_t>(::sysconf(_SC_PAGESIZE)) +
                       (rlim_t{2} << 30);
    if (old.rlim_cur != RLIM_INFINITY && old.rlim_cur < limited.rlim_cur)
        limited.rlim_cur = old.rlim_cur;
    ASSERT_EQ(::setrlimit(RLIMIT_AS, &limited), 0);
    bool renderError = false;
    std::string other;
    try {
        readPfm(path("huge.pfm"));
    } catch (const RenderError&) {
        renderError = true;
    } catch (const std::exception& e) {
        other = e.what();
    }
    ::setrlimit(RLIMIT_AS, &old);
    EXPECT_TRUE(renderError) << "threw: " << other;
#endif
}

TEST_F(ImageIo, ReadingAMissingOrNonImageFileIsARenderError) {
    EXPECT_THROW(readImage8(path("missing.png")), RenderError);
    writeBytes(dir_ / "text.png", "this is not a png");
    EXPECT_THROW(readImage8(path("text.png")), RenderError);
}

// ---- atomic writing ---------------------------------------------------------------------

TEST_F(ImageIo, SuccessfulWriteLeavesNoTemporaryFiles) {
    writeImage(path("out.png"), testFilm());
    writeImage(path("out.png"), testFilm());  // replacing an existing file
    writeImage(path("out.pfm"), testFilm());
    EXPECT_EQ(entries(), (std::set<std::string>{"out.png", "out.pfm"}));
}

TEST_F(ImageIo, WriteToAMissingDirectoryThrowsAndCreatesNothing) {
    try {
        writeImage(path("missing/out.png"), testFilm());
        FAIL() << "no RenderError";
    } catch (const RenderError& e) {
        EXPECT_THAT(e.what(), HasSubstr("missing/out.png"));
    }
    EXPECT_FALSE(fs::exists(dir_ / "missing"));
    EXPECT_TRUE(entries().empty());
}

TEST_F(ImageIo, UnknownExtensionThrowsAndCreatesNothing) {
    EXPECT_THROW(writeImage(path("out.jpg"), testFilm()), RenderError);
    EXPECT_TRUE(entries().empty());
}

TEST_F(ImageIo, FailedRenameLeavesWhatWasAtThePathUntouched) {
    // A non-empty directory cannot be replaced by a file, even by root.
    fs::create_directory(dir_ / "out.png");
    writeBytes(dir_ / "out.png" / "keep", "precious");
    EXPECT_THROW(writeImage(path("out.png"), testFilm()), RenderError);
    EXPECT_TRUE(fs::is_directory(dir_ / "out.png"));
    EXPECT_EQ(readBytes(dir_ / "out.png" / "keep"), "precious");
    EXPECT_EQ(entries(), (std::set<std::string>{"out.png"}));  // no temporary left behind
}

TEST_F(ImageIo, FailedWriteLeavesTheExistingFileUntouched) {
    // A file size limit makes write() fail part-way (EFBIG), whatever the user's privileges.
    writeBytes(dir_ / "out.ppm", "old image");
    rlimit old{};
    ASSERT_EQ(::getrlimit(RLIMIT_FSIZE, &old), 0);
    auto oldHandler = std::signal(SIGXFSZ, SIG_IGN);
    rlimit small = old;
    small.rlim_cur = 1000;
    ASSERT_EQ(::setrlimit(RLIMIT_FSIZE, &small), 0);
    Film big(64, 64);  // 12 KB of PPM
    bool threw = false;
    try {
        writeImage(path("out.ppm"), big);
    } catch (const RenderError&) {
        threw = true;
    }
    ::setrlimit(RLIMIT_FSIZE, &old);
    std::signal(SIGXFSZ, oldHandler);
    EXPECT_TRUE(threw);
    EXPECT_EQ(readBytes(dir_ / "out.ppm"), "old image");
    EXPECT_EQ(entries(), (std::set<std::string>{"out.ppm"}));
}

TEST_F(ImageIo, AtomicFileWritesAndReplacesTheExactBytes) {
    std::string bytes("a\0b\nc", 5);
    writeFileAtomically(path("f.bin"), bytes);
    EXPECT_EQ(readBytes(dir_ / "f.bin"), bytes);
    writeFileAtomically(path("f.bin"), "shorter");
    EXPECT_EQ(readBytes(dir_ / "f.bin"), "shorter");
    writeFileAtomically(path("empty"), "");
    EXPECT_TRUE(fs::exists(dir_ / "empty"));
    EXPECT_EQ(fs::file_size(dir_ / "empty"), 0u);
    EXPECT_EQ(entries(), (std::set<std::string>{"f.bin", "empty"}));
}

TEST_F(ImageIo, AtomicFileErrorNamesThePath) {
    try {
        writeFileAtomically(path("nowhere/f.bin"), "x");
        FAIL() << "no RenderError";
    } catch (const RenderError& e) {
        EXPECT_THAT(e.what(), HasSubstr("nowhere/f.bin"));
    }
    EXPECT_TRUE(entries().empty());
}

}  // namespace
}  // namespace glint
