// imgdiff as bench scripts use it: --blocks on float images (EXR, PFM) with known differences,
// --max-rel verdicts and exit codes, --ssim and --diff, --preview, the usage errors, and the
// grader's 8-bit mode.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <sstream>
#include <string>

#include "cli/cli_support.h"
#include "glint/io/image/image_io.h"

namespace glint::test {
namespace {

Film filledFilm(int w, int h, const Vec3& c) {
    Film f(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) f.at(x, y) = c;
    return f;
}

/// Multiplies the pixels of the block [x0, x0 + 16) x [y0, y0 + 16) by `k`.
void scaleBlock(Film& f, int x0, int y0, const Vec3& k) {
    for (int y = y0; y < y0 + 16; ++y)
        for (int x = x0; x < x0 + 16; ++x) f.at(x, y) = f.at(x, y) * k;
}

/// The value of `key=` on the output line that starts with `line`; NaN if there is none.
double valueOf(const std::string& out, const std::string& line, const std::string& key) {
    std::istringstream in(out);
    for (std::string l; std::getline(in, l);) {
        if (l.rfind(line + " ", 0) != 0) continue;
        size_t at = l.find(" " + key + "=");
        if (at == std::string::npos) break;
        return std::strtod(l.c_str() + at + key.size() + 2, nullptr);
    }
    return NAN;
}

const Vec3 kGrey{0.5, 0.25, 0.125};

/// A directory with ref.exr (64x48, constant) and a.exr, its copy with block (1, 2) 2%
/// brighter, b.pfm, a copy with block (3, 0) 10% bluer, and same.exr, an exact copy.
std::string imagesDir(const std::string& name) {
    std::string dir = freshDir(name);
    Film ref = filledFilm(64, 48, kGrey);
    writeImage(dir + "/ref.exr", ref);
    writeImage(dir + "/same.exr", ref);
    Film a = ref;
    scaleBlock(a, 16, 32, Vec3(1.02));
    writeImage(dir + "/a.exr", a);
    Film b = ref;
    scaleBlock(b, 48, 0, {1, 1, 1.1});
    writeImage(dir + "/b.pfm", b);
    return dir;
}

TEST(Imgdiff, IdenticalFloatImagesDifferByNothing) {
    std::string dir = imagesDir("same");
    CommandResult r = runImgdiff("--blocks 16 same.exr ref.exr --max-rel 0", dir);
    ASSERT_EQ(r.exitCode, 0) << r.out << r.err;
    EXPECT_TRUE(contains(r.out, "size       64x48, 12 blocks of 16x16 pixels")) << r.out;
    for (const char* key : {"r", "g", "b", "lum"}) {
        EXPECT_EQ(valueOf(r.out, "mean_rel", key), 0.0) << key;
        EXPECT_EQ(valueOf(r.out, "rmse", key), 0.0) << key;
    }
    EXPECT_EQ(valueOf(r.out, "block_rel", "lum"), 0.0);
    EXPECT_EQ(valueOf(r.out, "block_rel", "rgb"), 0.0);
    EXPECT_TRUE(contains(r.out, "PASSED")) << r.out;
}

TEST(Imgdiff, TwoPercentInOneBlockGivesTwoPercent) {
    std::string dir = imagesDir("block");
    CommandResult r = runImgdiff("--blocks 16 a.exr ref.exr", dir);
    ASSERT_EQ(r.exitCode, 0) << r.out << r.err;
    EXPECT_NEAR(valueOf(r.out, "block_rel", "lum"), 0.02, 1e-6) << r.out;
    EXPECT_NEAR(valueOf(r.out, "block_rel", "rgb"), 0.02, 1e-6) << r.out;
    EXPECT_TRUE(contains(r.out, "at=16,32")) << r.out;
    // One block of twelve: the image means differ by 0.02 / 12.
    EXPECT_NEAR(valueOf(r.out, "mean_rel", "lum"), 0.02 / 12, 1e-6) << r.out;
    EXPECT_NEAR(valueOf(r.out, "mean_rel", "b"), 0.02 / 12, 1e-6) << r.out;
    EXPECT_NEAR(valueOf(r.out, "mean_b", "r"), 0.5, 1e-6) << r.out;
    // 256 of 3072 pixels are off by 0.01 in red.
    EXPECT_NEAR(valueOf(r.out, "rmse", "r"), 0.01 * std::sqrt(256.0 / 3072), 1e-6) << r.out;
    EXPECT_FALSE(contains(r.out, "PASSED"));  // no verdict without --max-rel
}

TEST(Imgdiff, MaxRelFailsAboveTheLimit) {
    std::string dir = imagesDir("limit");
    CommandResult pass = runImgdiff("--blocks 16 a.exr ref.exr --max-rel 0.03", dir);
    EXPECT_EQ(pass.exitCode, 0) << pass.out << pass.err;
    EXPECT_TRUE(contains(pass.out, "PASSED: luminance")) << pass.out;
    CommandResult fail = runImgdiff("--blocks 16 a.exr ref.exr --max-rel 0.01", dir);
    EXPECT_EQ(fail.exitCode, 1) << fail.out << fail.err;
    EXPECT_TRUE(contains(fail.out, "FAILED: luminance")) << fail.out;
}

TEST(Imgdiff, RgbChecksEveryChannel) {
    // b.pfm: blue +10% in one block moves luminance by 0.0722 * 0.0125 / 0.294 = 0.3%.
    std::string dir = imagesDir("rgb");
    CommandResult r = runImgdiff("--blocks 16 b.pfm ref.exr --max-rel 0.05", dir);
    EXPECT_EQ(r.exitCode, 0) << r.out << r.err;
    EXPECT_NEAR(valueOf(r.out, "block_rel", "rgb"), 0.1, 1e-6) << r.out;
    EXPECT_TRUE(contains(r.out, "channel=b rgb_at=48,0")) << r.out;
    EXPECT_LT(valueOf(r.out, "block_rel", "lum"), 0.005) << r.out;
    CommandResult rgb = runImgdiff("--blocks 16 b.pfm ref.exr --max-rel 0.05 --rgb", dir);
    EXPECT_EQ(rgb.exitCode, 1) << rgb.out << rgb.err;
    EXPECT_TRUE(contains(rgb.out, "FAILED: largest channel")) << rgb.out;
}

TEST(Imgdiff, PreviewWritesAnSrgbPng) {
    std::string dir = imagesDir("preview");
    CommandResult r = runImgdiff("--preview ref.png ref.exr", dir);
    ASSERT_EQ(r.exitCode, 0) << r.out << r.err;
    Image8 img = readImage8(dir + "/ref.png", 3);
    ASSERT_EQ(img.width, 64);
    ASSERT_EQ(img.height, 48);
    EXPECT_EQ(img.at(10, 10, 0), 188);  // linear 0.5 through the sRGB curve
    r = runImgdiff("--preview dark.png --exposure -1 ref.exr", dir);
    ASSERT_EQ(r.exitCode, 0) << r.out << r.err;
    EXPECT_EQ(readImage8(dir + "/dark.png", 3).at(10, 10, 0), 137);  // 0.25
}

TEST(Imgdiff, SsimOfEqualImagesIsOneAndOfDifferentOnesLess) {
    std::string dir = imagesDir("ssim");
    CommandResult same = runImgdiff("--ssim same.exr ref.exr --min-ssim 1", dir);
    ASSERT_EQ(same.exitCode, 0) << same.out << same.err;
    EXPECT_DOUBLE_EQ(valueOf(same.out, "ssim", "mean"), 1.0) << same.out;
    EXPECT_EQ(valueOf(same.out, "ssim", "windows"), 54 * 38);
    EXPECT_EQ(valueOf(same.out, "lum", "mae_rel"), 0.0);
    EXPECT_TRUE(contains(same.out, "PASSED")) << same.out;
    // One 16x16 block of the 64x48 image 2% brighter: 1/12 of the pixels.
    CommandResult r = runImgdiff("--ssim a.exr ref.exr --min-ssim 0.999999 --diff d.png", dir);
    EXPECT_EQ(r.exitCode, 1) << r.out << r.err;
    EXPECT_TRUE(contains(r.out, "FAILED")) << r.out;
    double mean = valueOf(r.out, "ssim", "mean");
    EXPECT_LT(mean, 1.0);
    EXPECT_GT(mean, 0.99);
    EXPECT_NEAR(valueOf(r.out, "lum", "mean_rel"), 0.02 / 12, 1e-6) << r.out;
    EXPECT_NEAR(valueOf(r.out, "lum", "mae_rel"), 0.02 / 12, 1e-6) << r.out;
    // The difference picture: red (brighter) in that block, black elsewhere.
    Image8 d = readImage8(dir + "/d.png", 3);
    ASSERT_EQ(d.width, 64);
    EXPECT_GT(d.at(20, 40, 0), 0);
    EXPECT_EQ(d.at(20, 40, 2), 0);
    EXPECT_EQ(d.at(5, 5, 0), 0);
    EXPECT_EQ(d.at(5, 5, 2), 0);
}

TEST(Imgdiff, UsageErrorsExitTwo) {
    std::string dir = imagesDir("usage");
    for (const char* args :
         {"--blocks 16 a.exr", "--blocks 0 a.exr ref.exr",
          "--blocks 16 a.exr ref.exr --threshold 3", "--max-rel 0.1 a.exr ref.exr",
          "--blocks 16 --rgb a.exr ref.exr", "--blocks 16 --max-rel -1 a.exr ref.exr",
          "--blocks 16 --max-rel nan a.exr ref.exr", "--preview p.png a.exr ref.exr",
          "--exposure 1 a.exr ref.exr", "--preview p.exr a.exr", "--ssim a.exr",
          "--ssim --blocks 16 a.exr ref.exr", "--diff d.png a.exr ref.exr",
          "--ssim --diff-scale 2 a.exr ref.exr", "--ssim a.exr ref.exr --diff d.exr",
          "--min-ssim 0.5 a.exr ref.exr", "--preview p.png --ssim a.exr"}) {
        CommandResult r = runImgdiff(args, dir);
        EXPECT_EQ(r.exitCode, 2) << args << "\n" << r.out << r.err;
        EXPECT_FALSE(r.err.empty()) << args;
    }
}

TEST(Imgdiff, FloatImagesOnlyAndOfOneSize) {
    std::string dir = imagesDir("kinds");
    writeImage(dir + "/small.exr", filledFilm(32, 48, kGrey));
    writeImage(dir + "/ref.png", filledFilm(64, 48, kGrey));
    CommandResult r = runImgdiff("--blocks 16 small.exr ref.exr", dir);
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_TRUE(contains(r.err, "differ in size: 32x48 and 64x48")) << r.err;
    r = runImgdiff("--blocks 16 ref.png ref.exr", dir);
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_TRUE(contains(r.err, "'ref.png' is not a float image")) << r.err;
    r = runImgdiff("--blocks 16 missing.exr ref.exr", dir);
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_TRUE(contains(r.err, "missing.exr")) << r.err;
    r = runImgdiff("--ssim small.exr ref.exr", dir);
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_TRUE(contains(r.err, "differ in size")) << r.err;
    writeImage(dir + "/tiny.exr", filledFilm(10, 10, kGrey));
    r = runImgdiff("--ssim tiny.exr tiny.exr", dir);
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_TRUE(contains(r.err, "at least 11x11")) << r.err;
}

TEST(Imgdiff, GraderModeCountsHotPixels) {
    std::string dir = freshDir("grader");
    Film a = filledFilm(8, 8, Vec3(0.5));
    writeImage(dir + "/a.png", a);
    a.at(2, 3) = Vec3(0.6);
    writeImage(dir + "/b.png", a);
    CommandResult r = runImgdiff("a.png b.png", dir);
    EXPECT_EQ(r.exitCode, 0) << r.out << r.err;
    EXPECT_TRUE(contains(r.out, "threshold 2: 1 hot pixels")) << r.out;
    r = runImgdiff("a.png b.png --budget 0", dir);
    EXPECT_EQ(r.exitCode, 1) << r.out << r.err;
    EXPECT_TRUE(contains(r.out, "FAILED: 1/0 allowed hot pixels")) << r.out;
}

}  // namespace
}  // namespace glint::test
