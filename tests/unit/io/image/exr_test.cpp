// OpenEXR output and input: float round trips, what happens to values a float cannot hold,
// exposure, atomic writing, files from other writers (half, grey, offset data window) and
// malformed files.

#include "glint/io/image/exr.h"

#include <ImfBoxAttribute.h>
#include <ImfChannelList.h>
#include <ImfChromaticitiesAttribute.h>
#include <ImfDeepImageStateAttribute.h>
#include <ImfDoubleAttribute.h>
#include <ImfEnvmapAttribute.h>
#include <ImfFloatAttribute.h>
#include <ImfFloatVectorAttribute.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIntAttribute.h>
#include <ImfKeyCodeAttribute.h>
#include <ImfMatrixAttribute.h>
#include <ImfOpaqueAttribute.h>
#include <ImfOutputFile.h>
#include <ImfPreviewImageAttribute.h>
#include <ImfRationalAttribute.h>
#include <ImfStringAttribute.h>
#include <ImfStringVectorAttribute.h>
#include <ImfTileDescriptionAttribute.h>
#include <ImfTimeCodeAttribute.h>
#include <ImfVecAttribute.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <half.h>
#include <unistd.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <limits>
#include <set>

#include "glint/core/error.h"
#include "glint/io/image/image_io.h"
#include "unit/test_support.h"

namespace glint {
namespace {

using ::testing::HasSubstr;
namespace fs = std::filesystem;

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string readBytes(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void writeBytes(const fs::path& p, const std::string& bytes) {
    std::ofstream(p, std::ios::binary) << bytes;
}

/// Expects `got` to hold exactly `want` rounded to float, bit for bit (NaN as any NaN).
void expectFloatExact(const Film& want, const Film& got, double scale = 1) {
    ASSERT_EQ(got.width(), want.width());
    ASSERT_EQ(got.height(), want.height());
    for (int y = 0; y < want.height(); ++y)
        for (int x = 0; x < want.width(); ++x)
            for (int c = 0; c < 3; ++c) {
                float w = static_cast<float>(scale * want.at(x, y)[c]);
                double g = got.at(x, y)[c];
                if (std::isnan(w)) {
                    EXPECT_TRUE(std::isnan(g)) << x << "," << y << "," << c;
                    continue;
                }
                EXPECT_EQ(std::bit_cast<uint32_t>(static_cast<float>(g)),
                          std::bit_cast<uint32_t>(w))
                    << x << "," << y << "," << c << ": " << g << " vs " << w;
                EXPECT_EQ(g, static_cast<double>(w));  // float values come back unchanged
            }
}

/// A film of `w` x `h` with every pixel different, values spanning many decades.
Film rampFilm(int w, int h) {
    Film f(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            f.at(x, y) = {x / 7.0 + y * 0.001, std::pow(10.0, (x + y) % 40 - 20), -y / 3.0};
    return f;
}

class Exr : public test::TempDirTest {};

TEST(ExrFormat, ExtensionIsRecognisedIgnoringCase) {
    EXPECT_EQ(imageFormatFor("a.exr"), ImageFormat::Exr);
    EXPECT_EQ(imageFormatFor("out/A.EXR"), ImageFormat::Exr);
    EXPECT_EQ(imageFormatFor("a.exrx"), std::nullopt);
    EXPECT_TRUE(isFloatFormat(ImageFormat::Exr));
    EXPECT_TRUE(isFloatFormat(ImageFormat::Pfm));
    EXPECT_FALSE(isFloatFormat(ImageFormat::Png));
    EXPECT_FALSE(isFloatFormat(ImageFormat::Ppm));
}

TEST(ExrEncode, StartsWithTheOpenExrMagicNumber) {
    std::string bytes = encodeImage(rampFilm(5, 3), ImageFormat::Exr);
    ASSERT_GE(bytes.size(), 4u);
    EXPECT_EQ(bytes.substr(0, 4), std::string("\x76\x2f\x31\x01"));
}

TEST_F(Exr, RoundTripKeepsEveryFloatValueExactly) {
    // Above 1, negative, signed zeros, tiny (a float denormal) and huge (near the float maximum).
    Film f(4, 3);
    f.at(0, 0) = {1.5, -2.25, 1e-3};
    f.at(1, 0) = {1e30, -1e-30, 0.1};
    f.at(2, 0) = {0, -0.0, 12345.678};
    f.at(3, 0) = {0.7, 0.999, 100};
    f.at(0, 1) = {-7, 3.0e38, 1e-40};
    f.at(1, 1) = {0.5, 0.25, 0.125};
    f.at(2, 1) = {65504, 65536, 1e6};  // the half maximum and beyond: kept in float
    f.at(3, 1) = {6e-8, 1e-38, -3.4e38};
    f.at(0, 2) = {kInf, -kInf, 1.0};
    f.at(1, 2) = {0.1f, 1.0 / 3, 2.0 / 3};
    f.at(2, 2) = {1e-45, -1e-45, 1};  // the smallest float denormal
    f.at(3, 2) = {42, 0.001, -0.001};
    writeImage(path("a.exr"), f);
    Film g = readExr(path("a.exr"));
    expectFloatExact(f, g);
    EXPECT_EQ(g.at(0, 1).z, static_cast<double>(1e-40f));
    EXPECT_GT(g.at(0, 1).z, 0);  // denormals are not flushed to zero
    EXPECT_TRUE(std::signbit(g.at(2, 0).y));
    EXPECT_EQ(g.at(0, 2).x, kInf);
    EXPECT_EQ(g.at(0, 2).y, -kInf);
}

TEST_F(Exr, ValuesBeyondTheFloatRangeBecomeInfinitiesAndNaNStaysNaN) {
    Film f(2, 1);
    f.at(0, 0) = {1e300, -1e300, 1e-300};
    f.at(1, 0) = {kNaN, 1, 2};
    Film g = decodeExr(encodeExr(f), "mem.exr");
    EXPECT_EQ(g.at(0, 0).x, kInf);
    EXPECT_EQ(g.at(0, 0).y, -kInf);
    EXPECT_EQ(g.at(0, 0).z, 0.0);  // below the smallest float denormal
    EXPECT_TRUE(std::isnan(g.at(1, 0).x));
    EXPECT_EQ(g.at(1, 0).y, 1.0);
    EXPECT_EQ(g.at(1, 0).z, 2.0);
}

TEST_F(Exr, LargerImagesRoundTripAcrossChunkAndBatchBoundaries) {
    // 16-line ZIP chunks when writing, 64-row batches when reading: 150 rows cross both.
    for (auto [w, h] : {std::pair{1, 1}, {37, 23}, {200, 150}, {3, 129}}) {
        SCOPED_TRACE(std::to_string(w) + "x" + std::to_string(h));
        Film f = rampFilm(w, h);
        writeImage(path("r.exr"), f);
        expectFloatExact(f, readExr(path("r.exr")));
    }
}

TEST_F(Exr, ExposureScalesTheStoredValuesAndSrgbIsIgnored) {
    Film f = rampFilm(9, 5);
    const std::string plain = encodeImage(f, ImageFormat::Exr);
    const Film brighter = decodeExr(encodeImage(f, ImageFormat::Exr, {1}), "b.exr");
    expectFloatExact(f, brighter, 2);
    for (int x = 0; x < 9; ++x)
        EXPECT_EQ(brighter.at(x, 4).y, 2 * static_cast<float>(f.at(x, 4).y));
    expectFloatExact(f, decodeExr(encodeImage(f, ImageFormat::Exr, {-3}), "d.exr"), 0.125);
    EXPECT_EQ(encodeImage(f, ImageFormat::Exr, {0, true}), plain);  // linear, always
}

TEST_F(Exr, PfmTakesTheExposureTooAndMatchesTheExr) {
    Film f = rampFilm(6, 4);
    writeImage(path("a.pfm"), f, {2});
    writeImage(path("a.exr"), f, {2, true});
    expectFloatExact(f, readPfm(path("a.pfm")), 4);
    expectFloatExact(f, readExr(path("a.exr")), 4);
}

TEST_F(Exr, WriteIsAtomicAndLeavesNoTemporaryFiles) {
    writeImage(path("out.exr"), rampFilm(4, 4));
    writeImage(path("out.exr"), rampFilm(8, 2));  // replacing an existing file
    EXPECT_EQ(entries(), (std::set<std::string>{"out.exr"}));
    EXPECT_EQ(readExr(path("out.exr")).width(), 8);

    fs::create_directory(dir_ / "busy.exr");  // a non-empty directory cannot be replaced
    writeBytes(dir_ / "busy.exr" / "keep", "precious");
    EXPECT_THROW(writeImage(path("busy.exr"), rampFilm(2, 2)), RenderError);
    EXPECT_EQ(readBytes(dir_ / "busy.exr" / "keep"), "precious");
    EXPECT_EQ(entries(), (std::set<std::string>{"out.exr", "busy.exr"}));
    EXPECT_THROW(writeImage(path("missing/out.exr"), rampFilm(2, 2)), RenderError);
}

// ---- files written by other programs ----------------------------------------------------

/// Writes an EXR with OpenEXR directly: the given channels, all of `type`, every channel of
/// pixel (x, y) set to value(x, y, channel index), over `window`, and whatever `more` adds to
/// the header.
template <typename T, typename F>
void writeWithOpenExr(const std::string& path, Imf::PixelType type,
                      const std::vector<const char*>& names, const Imath::Box2i& window, F value,
                      const std::function<void(Imf::Header&)>& more = {}) {
    const int w = window.max.x - window.min.x + 1, h = window.max.y - window.min.y + 1;
    const size_t n = names.size();
    std::vector<T> data(static_cast<size_t>(w) * h * n);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (size_t c = 0; c < n; ++c)
                data[(static_cast<size_t>(y) * w + x) * n + c] =
                    static_cast<T>(static_cast<float>(value(x, y, static_cast<int>(c))));
    Imf::Header header(window, window);
    Imf::FrameBuffer frame;
    for (size_t c = 0; c < n; ++c) {
        header.channels().insert(names[c], Imf::Channel(type));
        frame.insert(names[c], Imf::Slice::Make(type, data.data() + c, window, n * sizeof(T),
                                                n * sizeof(T) * w));
    }
    if (more) more(header);
    Imf::OutputFile file(path.c_str(), header);
    file.setFrameBuffer(frame);
    file.writePixels(h);
}

TEST_F(Exr, ReadsHalfChannelsExactly) {
    // Half holds these exactly: powers of two, the half maximum, a half denormal, negatives.
    const double values[] = {0.5, 65504, -2, 0.099975586, 5.9604645e-8, 1, 1024, -0.25, 0};
    writeWithOpenExr<half>(path("h.exr"), Imf::HALF, {"B", "G", "R"}, Imath::Box2i({0, 0}, {2, 0}),
                           [&](int x, int, int c) { return values[x * 3 + c]; });
    Film f = readExr(path("h.exr"));
    ASSERT_EQ(f.width(), 3);
    ASSERT_EQ(f.height(), 1);
    for (int x = 0; x < 3; ++x)  // channels are matched by name, not by order in the file
        EXPECT_EQ(f.at(x, 0), Vec3(static_cast<float>(half(static_cast<float>(values[x * 3 + 2]))),
                                   static_cast<float>(half(static_cast<float>(values[x * 3 + 1]))),
                                   static_cast<float>(half(static_cast<float>(values[x * 3])))));
    EXPECT_EQ(f.at(0, 0), Vec3(-2, 65504, 0.5));
}

TEST_F(Exr, ReadsAGreyYChannelIntoAllThree) {
    writeWithOpenExr<float>(path("y.exr"), Imf::FLOAT, {"Y"}, Imath::Box2i({0, 0}, {3, 1}),
                            [](int x, int y, int) { return x + 10.0 * y - 5; });
    Film f = readExr(path("y.exr"));
    ASSERT_EQ(f.width(), 4);
    ASSERT_EQ(f.height(), 2);
    EXPECT_EQ(f.at(0, 0), Vec3(-5));
    EXPECT_EQ(f.at(3, 1), Vec3(8));
}

TEST_F(Exr, ADataWindowAwayFromTheOriginBecomesTheFilm) {
    writeWithOpenExr<float>(path("w.exr"), Imf::FLOAT, {"R", "G", "B"},
                            Imath::Box2i({-3, 100}, {1, 170}),
                            [](int x, int y, int c) { return x + 1000.0 * y + 0.25 * c; });
    Film f = readExr(path("w.exr"));
    ASSERT_EQ(f.width(), 5);
    ASSERT_EQ(f.height(), 71);
    EXPECT_EQ(f.at(0, 0), Vec3(0, 0.25, 0.5));
    EXPECT_EQ(f.at(4, 70), Vec3(70004, 70004.25, 70004.5));
}

// ---- bad files --------------------------------------------------------------------------

TEST_F(Exr, MissingTruncatedOrForeignFilesAreRenderErrors) {
    EXPECT_THROW(readExr(path("missing.exr")), RenderError);
    writeBytes(dir_ / "empty.exr", "");
    EXPECT_THROW(readExr(path("empty.exr")), RenderError);
    writeBytes(dir_ / "text.exr", "this is not an exr file at all");
    EXPECT_THROW(readExr(path("text.exr")), RenderError);
    const std::string good = encodeExr(rampFilm(40, 40));
    for (size_t cut : {size_t{3}, size_t{40}, good.size() / 2, good.size() - 1}) {
        SCOPED_TRACE(cut);
        try {
            decodeExr(std::string_view(good).substr(0, cut), "cut.exr");
            FAIL() << "no RenderError";
        } catch (const RenderError& e) {
            EXPECT_THAT(e.what(), HasSubstr("cannot read image 'cut.exr'"));
        }
    }
}

TEST_F(Exr, FilesWithoutColourChannelsAreRejectedByName) {
    writeWithOpenExr<float>(path("z.exr"), Imf::FLOAT, {"Z"}, Imath::Box2i({0, 0}, {1, 1}),
                            [](int, int, int) { return 1.0; });
    try {
        readExr(path("z.exr"));
        FAIL() << "no RenderError";
    } catch (const RenderError& e) {
        EXPECT_THAT(e.what(), HasSubstr("no R, G, B or Y channels"));
    }
}

TEST_F(Exr, AHeaderClaimingAHugeImageIsRejectedBeforeAllocatingIt) {
    // Patch the data window of a small file to 100000 x 1 pixels: beyond Glint's image limits.
    std::string bytes = encodeExr(rampFilm(2, 2));
    const std::string key("dataWindow\0box2i\0", 17);
    size_t at = bytes.find(key);
    ASSERT_NE(at, std::string::npos);
    at += key.size() + 4 + 8;  // size, then xMin and yMin: xMax follows
    const int32_t xMax = 99999;
    std::memcpy(bytes.data() + at, &xMax, 4);
    EXPECT_THROW(decodeExr(bytes, "huge.exr"), RenderError);
}

/// The check of attribute sizes before OpenEXR reads a header (exr_streams.h) walks the header
/// as OpenEXR does, which reads most types by their own layout, not by the size they claim. So
/// it must know every type's layout to find the claim of the attribute after it: here every
/// type OpenEXR 3.1 writes (but idmanifest) and one it does not know, then a string that
/// claims 1 GB.
TEST_F(Exr, AttributeSizesAreCheckedPastEveryTypeOfAttribute) {
    auto everyType = [](Imf::Header& h) {
        using namespace Imf;
        h.insert("a.box2f", Box2fAttribute({{0, 1}, {2, 3}}));
        h.insert("a.chromaticities", ChromaticitiesAttribute(Chromaticities()));
        h.insert("a.deepImageState", DeepImageStateAttribute(DIS_TIDY));
        h.insert("a.double", DoubleAttribute(0.5));
        h.insert("a.envmap", EnvmapAttribute(ENVMAP_CUBE));
        h.insert("a.float", FloatAttribute(2));
        h.insert("a.floatvector", FloatVectorAttribute({1, 2, 3}));
        h.insert("a.int", IntAttribute(7));
        h.insert("a.keycode", KeyCodeAttribute(KeyCode(1, 2, 3, 4, 5, 4, 64)));
        h.insert("a.m33d", M33dAttribute(Imath::M33d()));
        h.insert("a.m33f", M33fAttribute(Imath::M33f()));
        h.insert("a.m44d", M44dAttribute(Imath::M44d()));
        h.insert("a.m44f", M44fAttribute(Imath::M44f()));
        h.insert("a.opaque", OpaqueAttribute("someType"));
        h.insert("a.preview", PreviewImageAttribute(PreviewImage(3, 2)));
        h.insert("a.rational", RationalAttribute(Rational(1, 3)));
        h.insert("a.stringvector", StringVectorAttribute({"one", "", "three"}));
        h.insert("a.tiledesc", TileDescriptionAttribute(TileDescription(16, 8)));
        h.insert("a.timecode", TimeCodeAttribute(TimeCode(1, 2, 3, 4)));
        h.insert("a.v2d", V2dAttribute({1, 2}));
        h.insert("a.v2f", V2fAttribute({1, 2}));
        h.insert("a.v2i", V2iAttribute({1, 2}));
        h.insert("a.v3d", V3dAttribute({1, 2, 3}));
        h.insert("a.v3f", V3fAttribute({1, 2, 3}));
        h.insert("a.v3i", V3iAttribute({1, 2, 3}));
        h.insert("zz.last", StringAttribute("written after all the others"));
    };
    writeWithOpenExr<float>(
        path("all.exr"), Imf::FLOAT, {"R", "G", "B", "A", "Z"}, Imath::Box2i({0, 0}, {1, 1}),
        [](int x, int, int) { return x; }, everyType);
    std::string bytes = readBytes(path("all.exr"));
    EXPECT_EQ(decodeExr(bytes, "all.exr").at(1, 0), Vec3(1));
    const std::string key("zz.last\0string\0", 15);
    const size_t at = bytes.find(key);
    ASSERT_NE(at, std::string::npos);
    ASSERT_LT(bytes.find("a.v3i"), at);  // attributes are written in the order of their names
    const int32_t claim = 1 << 30;
    std::memcpy(bytes.data() + at + key.size(), &claim, 4);
    try {
        decodeExr(bytes, "all.exr");
        FAIL() << "no RenderError";
    } catch (const RenderError& e) {
        EXPECT_THAT(e.what(), HasSubstr("attribute 'zz.last' claims 1073741824 bytes"));
    }
}

}  // namespace
}  // namespace glint
