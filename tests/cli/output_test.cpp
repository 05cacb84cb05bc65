// Output that keeps the full range (-o x.exr) and the display options for 8-bit outputs
// (--exposure, --srgb), as users meet them. Every 8-bit image here is checked against the
// float image of the same render, so each option is tested for what it does to the values.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "cli/cli_support.h"
#include "glint/io/image/image_io.h"
#include "glint/render/film/display.h"

namespace glint::test {
namespace {

namespace fs = std::filesystem;

/// A small scene bright enough that some pixels go above 1 (the emissive sphere, the lit
/// floor), with mirror reflections and shadows for a spread of values below.
const char* const kBrightScene =
    "size 64 48\n"
    "camera 0 1 6 0 0 0 0 1 0 45\n"
    "maxdepth 2\n"
    "point 3 4 5 2.5 2.5 2.5\n"
    "directional 0 1 1 0.3 0.3 0.3\n"
    "ambient 0.05 0.05 0.05\n"
    "diffuse 0.5 0.4 0.3\n"
    "vertex -3 -1 -3\n"
    "vertex 3 -1 -3\n"
    "vertex 3 -1 3\n"
    "vertex -3 -1 3\n"
    "tri 0 2 1\n"
    "tri 0 3 2\n"
    "specular 0.8 0.8 0.8\n"
    "sphere -1 0 0 1\n"
    "emission 1.5 0.2 0.1\n"
    "sphere 1.2 0 -0.5 0.8\n";

std::string brightDir(const std::string& name) {
    std::string dir = freshDir(name);
    writeFile(dir + "/scene.test", kBrightScene);
    return dir;
}

/// Renders scene.test in `dir` with `args` to `file` and expects success.
void render(const std::string& dir, const std::string& args, const std::string& file) {
    CommandResult r = runGlint("-q scene.test " + args + " -o " + file, dir);
    ASSERT_EQ(r.exitCode, 0) << args << " -o " << file << ": " << r.err;
}

/// Compares an 8-bit image with `byte` applied to each value of the float image `linear`.
/// The film is double and the EXR float, so a value within a float rounding of a level
/// boundary may land one level off: allow that for at most 1% of the channels.
template <typename Byte>
void expectBytesOf(const Image8& img, const Film& linear, Byte byte) {
    ASSERT_EQ(img.width, linear.width());
    ASSERT_EQ(img.height, linear.height());
    int offByOne = 0;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x)
            for (int c = 0; c < 3; ++c) {
                int want = byte(linear.at(x, y)[c]), got = img.at(x, y, c);
                ASSERT_LE(std::abs(got - want), 1) << x << "," << y << "," << c;
                offByOne += got != want;
            }
    EXPECT_LE(offByOne, img.width * img.height * 3 / 100);
}

/// Sums of the bytes, and how many channels of `a` are above, below or equal to `b`'s.
struct Compare {
    int above = 0, below = 0;
};
Compare compare(const Image8& a, const Image8& b) {
    Compare r;
    for (size_t i = 0; i < a.data.size(); ++i) {
        r.above += a.data[i] > b.data[i];
        r.below += a.data[i] < b.data[i];
    }
    return r;
}

TEST(CliOutput, ExrIsAReadableFloatImageHoldingThePfmValues) {
    std::string dir = brightDir("exr");
    CommandResult r = runGlint("scene.test -o out.exr", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(contains(r.err, "glint: wrote out.exr (64x48)")) << r.err;
    EXPECT_EQ(readBytes(dir + "/out.exr").substr(0, 4), std::string("\x76\x2f\x31\x01"));
    Film exr = readExr(dir + "/out.exr");
    ASSERT_EQ(exr.width(), 64);
    ASSERT_EQ(exr.height(), 48);

    render(dir, "", "out.pfm");
    Film pfm = readPfm(dir + "/out.pfm");
    double brightest = 0;
    for (int y = 0; y < 48; ++y)
        for (int x = 0; x < 64; ++x) {
            ASSERT_EQ(exr.at(x, y), pfm.at(x, y)) << x << "," << y;
            brightest = std::max({brightest, exr.at(x, y).x, exr.at(x, y).y, exr.at(x, y).z});
        }
    EXPECT_GT(brightest, 1.0) << "unclamped: the scene has values above 1";

    render(dir, "--size 37x21", "small.EXR");
    Film small = readExr(dir + "/small.EXR");
    EXPECT_EQ(small.width(), 37);
    EXPECT_EQ(small.height(), 21);
}

TEST(CliOutput, DefaultPngIsStillTheCoursesClampAndFloor) {
    std::string dir = brightDir("default");
    render(dir, "", "lin.exr");
    render(dir, "", "default.png");
    render(dir, "--exposure 0", "zero.png");
    Film linear = readExr(dir + "/lin.exr");
    expectBytesOf(readImage8(dir + "/default.png", 3), linear, [](double c) { return toByte(c); });
    EXPECT_EQ(readBytes(dir + "/zero.png"), readBytes(dir + "/default.png"));
}

TEST(CliOutput, ExposureScalesFloatOutputsByTwoToTheEv) {
    std::string dir = brightDir("expfloat");
    render(dir, "", "lin.exr");
    render(dir, "--exposure 1", "up.exr");
    render(dir, "--exposure=-2", "down.pfm");
    render(dir, "--exposure 0.5", "half.exr");
    Film lin = readExr(dir + "/lin.exr"), up = readExr(dir + "/up.exr");
    Film down = readPfm(dir + "/down.pfm"), half = readExr(dir + "/half.exr");
    for (int y = 0; y < 48; ++y)
        for (int x = 0; x < 64; ++x)
            for (int c = 0; c < 3; ++c) {
                double v = lin.at(x, y)[c];
                ASSERT_EQ(up.at(x, y)[c], 2 * v) << x << "," << y;  // powers of two: exact
                ASSERT_EQ(down.at(x, y)[c], v / 4) << x << "," << y;
                ASSERT_NEAR(half.at(x, y)[c], v * std::sqrt(2.0), 1e-6 * v) << x << "," << y;
            }
}

TEST(CliOutput, ExposureScalesBeforeTheCoursesFloorInPngAndPpm) {
    std::string dir = brightDir("exp8");
    render(dir, "", "lin.exr");
    render(dir, "", "default.png");
    render(dir, "--exposure 1", "up.png");
    render(dir, "--exposure -1", "down.ppm");
    Film linear = readExr(dir + "/lin.exr");
    Image8 base = readImage8(dir + "/default.png", 3), up = readImage8(dir + "/up.png", 3);
    Image8 down = readImage8(dir + "/down.ppm", 3);
    expectBytesOf(up, linear, [](double c) { return toByte(2 * c); });
    expectBytesOf(down, linear, [](double c) { return toByte(c / 2); });
    Compare u = compare(up, base), d = compare(down, base);
    EXPECT_EQ(u.below, 0);
    EXPECT_GT(u.above, 1000);
    EXPECT_EQ(d.above, 0);
    EXPECT_GT(d.below, 1000);
}

TEST(CliOutput, SrgbEncodesPngAndPpmWithTheRoundedCurve) {
    std::string dir = brightDir("srgb");
    render(dir, "", "lin.exr");
    render(dir, "", "default.png");
    render(dir, "--srgb", "s.png");
    render(dir, "--srgb", "s.ppm");
    render(dir, "--srgb --exposure -1", "sdown.png");
    Film linear = readExr(dir + "/lin.exr");
    Image8 base = readImage8(dir + "/default.png", 3), s = readImage8(dir + "/s.png", 3);
    expectBytesOf(s, linear, [](double c) { return toByteSrgb(c); });
    expectBytesOf(readImage8(dir + "/sdown.png", 3), linear,
                  [](double c) { return toByteSrgb(c / 2); });
    EXPECT_EQ(readImage8(dir + "/s.ppm", 3).data, s.data);
    Compare c = compare(s, base);  // the curve lifts every value below 1, rounding never lowers
    EXPECT_EQ(c.below, 0);
    EXPECT_GT(c.above, 1000);
}

TEST(CliOutput, SrgbWithAFloatOutputWarnsAndWritesLinearValues) {
    std::string dir = brightDir("srgbfloat");
    render(dir, "", "lin.exr");
    for (const char* out : {"s.exr", "s.pfm"}) {
        SCOPED_TRACE(out);
        CommandResult r = runGlint(std::string("-q scene.test --srgb -o ") + out, dir);
        ASSERT_EQ(r.exitCode, 0) << r.err;
        EXPECT_EQ(r.err, std::string("glint: warning: --srgb applies to 8-bit outputs (.png, "
                                     ".ppm) only; '") +
                             out + "' is written linear\n");
    }
    Film lin = readExr(dir + "/lin.exr"), s = readExr(dir + "/s.exr"), p = readPfm(dir + "/s.pfm");
    for (int y = 0; y < 48; ++y)
        for (int x = 0; x < 64; ++x) {
            ASSERT_EQ(s.at(x, y), lin.at(x, y));
            ASSERT_EQ(p.at(x, y), lin.at(x, y));
        }
}

TEST(CliOutput, ExposureMustBeAFiniteNumberWithinRange) {
    std::string dir = brightDir("expbad");
    for (const char* bad : {"abc", "1e3", "65", "-64.5", "nan", "inf", "1ev", "''"}) {
        SCOPED_TRACE(bad);
        CommandResult r = runGlint(std::string("scene.test -o x.png --exposure ") + bad, dir);
        EXPECT_EQ(r.exitCode, 2);
        EXPECT_TRUE(contains(r.err, "glint: error: --exposure")) << r.err;
        EXPECT_TRUE(contains(r.err, "Run 'glint --help' for usage.")) << r.err;
    }
    CommandResult r = runGlint("scene.test -o x.png --exposure abc", dir);
    EXPECT_TRUE(contains(r.err, "expected a number, got 'abc'")) << r.err;
    r = runGlint("scene.test -o x.png --exposure 65", dir);
    EXPECT_TRUE(contains(r.err, "must be -64 to 64, got 65")) << r.err;
    r = runGlint("scene.test -o x.png --exposure", dir);
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_FALSE(fs::exists(dir + "/x.png"));
    r = runGlint("-q scene.test -o x.png --exposure -64", dir);  // the limits themselves are fine
    EXPECT_EQ(r.exitCode, 0) << r.err;
}

TEST(CliOutput, HelpListsTheDisplayOptionsAndExr) {
    CommandResult r = runGlint("--help", freshDir("outhelp"));
    EXPECT_EQ(r.exitCode, 0);
    for (const char* text : {"--exposure EV", "--srgb", ".exr"})
        EXPECT_TRUE(contains(r.out, text)) << text << " missing from:\n" << r.out;
}

}  // namespace
}  // namespace glint::test
