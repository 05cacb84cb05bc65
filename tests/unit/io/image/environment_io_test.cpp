// Reading environment maps: Radiance HDR (written here with stb_image_write) and OpenEXR
// (written with Glint's encoder) give the radiance written; other files, truncated files and
// images beyond the limits give messages that name the file and the reason.

#include "glint/io/image/environment_io.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <stb_image_write.h>

#include <fstream>

#include "glint/core/error.h"
#include "glint/io/image/exr.h"
#include "glint/io/image/image_io.h"
#include "unit/test_support.h"

namespace glint {
namespace {

using ::testing::HasSubstr;

class EnvironmentIo : public test::TempDirTest {
  protected:
    void writeBytes(const std::string& name, const std::string& bytes) {
        std::ofstream(path(name), std::ios::binary) << bytes;
    }
    /// The message of the RenderError that reading `name` throws.
    std::string errorOf(const std::string& name, const LoadLimits& limits = {}) {
        try {
            loadEnvironmentImage(path(name), limits);
        } catch (const RenderError& e) {
            return e.what();
        }
        ADD_FAILURE() << "no error for " << name;
        return {};
    }
};

/// 4 x 2 texels, each value exact in RGBE (8 bits of mantissa under the largest channel's
/// exponent) and in float, different in every texel and channel.
std::vector<float> testTexels() {
    return {1,    0.5f,  0.25f, 2,  3, 0.5f, 0.125f, 0,     0.0625f, 8,     4, 2,
            0.5f, 0.75f, 0.25f, 16, 1, 0,    0.25f,  0.25f, 0.25f,   0.75f, 1, 0.5f};
}

TEST_F(EnvironmentIo, RadianceHdrGivesTheRadianceWritten) {
    std::vector<float> rgb = testTexels();
    ASSERT_TRUE(stbi_write_hdr(path("sky.hdr").c_str(), 4, 2, 3, rgb.data()));
    HdrImage img = loadEnvironmentImage(path("sky.hdr"));
    EXPECT_EQ(img.width, 4);
    EXPECT_EQ(img.height, 2);
    EXPECT_EQ(img.rgb, rgb);  // row 0 first, as written
}

TEST_F(EnvironmentIo, OpenExrGivesTheRadianceWritten) {
    std::vector<float> rgb = testTexels();
    Film film(4, 2);
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 4; ++x) {
            const float* p = &rgb[static_cast<size_t>(y * 4 + x) * 3];
            film.at(x, y) = Vec3(p[0], p[1], p[2]);
        }
    film.at(3, 1) = Vec3(1e6, 1e-6, 123.456);  // floats beyond RGBE's range and precision
    writeBytes("sky.exr", encodeExr(film));
    HdrImage img = loadEnvironmentImage(path("sky.exr"));
    EXPECT_EQ(img.width, 4);
    EXPECT_EQ(img.height, 2);
    rgb[21] = 1e6f;
    rgb[22] = 1e-6f;
    rgb[23] = 123.456f;
    EXPECT_EQ(img.rgb, rgb);
}

TEST_F(EnvironmentIo, TheFormatIsToldByTheFirstBytes) {
    // An EXR named .hdr is read as EXR (and the other way round).
    Film film(2, 1);
    film.at(1, 0) = Vec3(5, 6, 7);
    writeBytes("really-exr.hdr", encodeExr(film));
    EXPECT_EQ(loadEnvironmentImage(path("really-exr.hdr")).rgb[5], 7);
    std::vector<float> rgb = {1, 2, 4, 8, 16, 32};
    ASSERT_TRUE(stbi_write_hdr(path("really-hdr.exr").c_str(), 2, 1, 3, rgb.data()));
    EXPECT_EQ(loadEnvironmentImage(path("really-hdr.exr")).rgb, rgb);
}

TEST_F(EnvironmentIo, OtherFilesAreRefusedWithTheReason) {
    std::string missing = errorOf("nowhere.hdr");
    EXPECT_THAT(missing, HasSubstr("cannot read environment map '" + path("nowhere.hdr") + "'"));
    EXPECT_THAT(missing, HasSubstr("No such file or directory"));
    std::filesystem::create_directory(path("dir.hdr"));
    EXPECT_THAT(errorOf("dir.hdr"), HasSubstr("it is a directory"));

    writeBytes("empty.hdr", "");
    EXPECT_THAT(errorOf("empty.hdr"), HasSubstr("the file is empty"));
    writeBytes("text.hdr", "sphere 0 0 0 1\n");
    EXPECT_THAT(errorOf("text.hdr"), HasSubstr("not a Radiance HDR (.hdr) or OpenEXR (.exr) file"));
    Film film(2, 2);
    writeImage(path("ldr.png"), film);
    EXPECT_THAT(errorOf("ldr.png"),
                HasSubstr("it is an 8-bit image, not a high-dynamic-range one: environment "
                          "maps are Radiance HDR (.hdr) or OpenEXR (.exr) files"));
}

TEST_F(EnvironmentIo, TruncatedFilesAreRefused) {
    std::vector<float> rgb(64 * 8 * 3, 0.5f);
    ASSERT_TRUE(stbi_write_hdr(path("full.hdr").c_str(), 64, 8, 3, rgb.data()));
    std::ifstream in(path("full.hdr"), std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    writeBytes("cut.hdr", bytes.substr(0, bytes.size() / 2));
    EXPECT_THAT(errorOf("cut.hdr"), HasSubstr("cannot read environment map '" + path("cut.hdr") +
                                              "': not a valid Radiance HDR file ("));

    Film film(64, 8);
    std::string exr = encodeExr(film);
    writeBytes("cut.exr", exr.substr(0, exr.size() - 40));
    EXPECT_THAT(errorOf("cut.exr"), HasSubstr("cannot read image '" + path("cut.exr") + "': "));
    writeBytes("header.exr", exr.substr(0, 20));
    EXPECT_THAT(errorOf("header.exr"),
                HasSubstr("cannot read image '" + path("header.exr") + "': "));
}

TEST_F(EnvironmentIo, ImagesBeyondTheLimitsAreRefusedBeforeDecoding) {
    // The header claims 40000 x 10 pixels; no pixel data follows.
    writeBytes("wide.hdr", "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 10 +X 40000\n");
    EXPECT_THAT(errorOf("wide.hdr"),
                HasSubstr("the image is 40000 x 10 pixels; environment maps may have at most "
                          "32768 on a side and 134217728 in all"));
    writeBytes("huge.hdr", "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 20000 +X 20000\n");
    EXPECT_THAT(errorOf("huge.hdr"), HasSubstr("the image is 20000 x 20000 pixels"));
    // Within the size limits but not the memory allowed.
    std::vector<float> rgb(64 * 32 * 3, 1.0f);
    ASSERT_TRUE(stbi_write_hdr(path("sky.hdr").c_str(), 64, 32, 3, rgb.data()));
    Film film(64, 32);
    writeBytes("sky.exr", encodeExr(film));
    LoadLimits tight;
    tight.memoryBytes = 10000;
    for (const char* name : {"sky.hdr", "sky.exr"})
        EXPECT_THAT(errorOf(name, tight),
                    HasSubstr("reading and sampling it needs about 0 MiB, more than the 0 MiB "
                              "available"));
    EXPECT_EQ(loadEnvironmentImage(path("sky.hdr")).width, 64);
}

}  // namespace
}  // namespace glint
