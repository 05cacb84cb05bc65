#include "glint/io/image/image_diff.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "glint/math/rng.h"

namespace glint {
namespace {

Image8 filled(int w, int h, uint8_t value, int channels = 3) {
    Image8 img{w, h, channels, {}};
    img.data.assign(static_cast<size_t>(w) * h * channels, value);
    return img;
}

void set(Image8& img, int x, int y, int c, int value) {
    img.data[(static_cast<size_t>(y) * img.width + x) * img.channels + c] =
        static_cast<uint8_t>(value);
}

// A 4 x 2 image of level 100 and a copy with per-pixel differences, largest channel:
// (0,0): 1 (green), (1,0): 2 (blue, negative), (2,0): 3 (red), (3,0): 10 and 1, (0,1): 255.
struct Pair {
    Image8 a = filled(4, 2, 100), b = filled(4, 2, 100);
    Pair() {
        set(a, 0, 0, 1, 101);
        set(b, 1, 0, 2, 98);
        set(b, 2, 0, 0, 103);
        set(a, 3, 0, 0, 110);
        set(b, 3, 0, 1, 101);
        set(a, 0, 1, 2, 0);
        set(b, 0, 1, 2, 255);
    }
};

TEST(ImageDiff, HotPixelsExceedTheThresholdInTheirLargestChannel) {
    Pair p;
    EXPECT_EQ(countHotPixels(p.a, p.b, 0), 5);
    EXPECT_EQ(countHotPixels(p.a, p.b, 1), 4);  // differences of exactly 1 are not hot
    EXPECT_EQ(countHotPixels(p.a, p.b, 2), 3);
    EXPECT_EQ(countHotPixels(p.a, p.b, 3), 2);
    EXPECT_EQ(countHotPixels(p.a, p.b, 10), 1);
    EXPECT_EQ(countHotPixels(p.a, p.b, 255), 0);
    // Symmetric in its arguments.
    EXPECT_EQ(countHotPixels(p.b, p.a, 2), 3);
}

TEST(ImageDiff, IdenticalImagesHaveNoHotPixels) {
    Pair p;
    EXPECT_EQ(countHotPixels(p.a, p.a, 0), 0);
    EXPECT_EQ(maxChannelDifference(p.b, p.b), 0);
}

TEST(ImageDiff, MaskedPixelsAreSkipped) {
    Pair p;
    Image8 mask = filled(4, 2, 0, 1);
    set(mask, 0, 1, 0, 255);  // hide the 255 difference
    set(mask, 2, 0, 0, 1);    // any non-zero value masks
    EXPECT_EQ(countHotPixels(p.a, p.b, 0, &mask), 3);
    EXPECT_EQ(countHotPixels(p.a, p.b, 2, &mask), 1);
    EXPECT_EQ(maxChannelDifference(p.a, p.b, &mask), 10);
}

TEST(ImageDiff, MaxChannelDifferenceIsTheLargestOverPixelsAndChannels) {
    Pair p;
    EXPECT_EQ(maxChannelDifference(p.a, p.b), 255);
    Image8 c = filled(4, 2, 100);
    set(c, 3, 1, 2, 93);
    EXPECT_EQ(maxChannelDifference(filled(4, 2, 100), c), 7);
}

TEST(ImageDiff, MismatchedSizesOrChannelsAreRejected) {
    Image8 a = filled(4, 2, 0);
    EXPECT_THROW(countHotPixels(a, filled(2, 4, 0), 1), std::invalid_argument);
    EXPECT_THROW(countHotPixels(a, filled(4, 2, 0, 1), 1), std::invalid_argument);
    EXPECT_THROW(maxChannelDifference(filled(4, 2, 0, 4), filled(4, 2, 0, 4)),
                 std::invalid_argument);
    Image8 smallMask = filled(2, 2, 0, 1);
    EXPECT_THROW(countHotPixels(a, a, 1, &smallMask), std::invalid_argument);
    EXPECT_THROW(meanAbsDifference(a, filled(4, 3, 0)), std::invalid_argument);
    EXPECT_THROW(countHotBlocks(a, filled(4, 3, 0), 1, 1.0), std::invalid_argument);
}

TEST(ImageDiff, HotBlocksCompareBlockAverages) {
    // 4 x 4 images, blocks of 2 x 2 (four blocks).
    Image8 a = filled(4, 4, 50), b = filled(4, 4, 50);
    set(b, 0, 0, 0, 58);  // top-left block: red average +2
    set(b, 3, 0, 1, 54);  // top-right block: green +4 and -4 cancel in the average
    set(b, 2, 1, 1, 46);
    set(b, 1, 3, 2, 53);                         // bottom-left block: blue average +0.75
    set(b, 2, 2, 0, 48);                         // bottom-right block: red -0.5 ...
    set(b, 3, 3, 2, 56);                         // ... and blue +1.5
    EXPECT_EQ(countHotBlocks(a, b, 2, 0.0), 3);  // the cancelling block is never hot
    EXPECT_EQ(countHotBlocks(a, b, 2, 0.7), 3);
    EXPECT_EQ(countHotBlocks(a, b, 2, 0.75), 2);  // strictly greater
    EXPECT_EQ(countHotBlocks(a, b, 2, 1.5), 1);
    EXPECT_EQ(countHotBlocks(a, b, 2, 2.0), 0);
    // One block covering everything: red (8 - 2) / 16, green 0, blue (3 + 6) / 16 = 0.5625.
    EXPECT_EQ(countHotBlocks(a, b, 4, 0.56), 1);
    EXPECT_EQ(countHotBlocks(a, b, 4, 0.5625), 0);
    // Blocks of one pixel are plain per-pixel comparisons: 6 pixels differ by more than 1.
    EXPECT_EQ(countHotBlocks(a, b, 1, 1.0), 6);
}

TEST(ImageDiff, HotBlocksNeedSizesThatAreMultiplesOfTheBlock) {
    Image8 a = filled(6, 4, 0);
    EXPECT_THROW(countHotBlocks(a, a, 4, 1.0), std::invalid_argument);
    EXPECT_THROW(countHotBlocks(a, a, 0, 1.0), std::invalid_argument);
    EXPECT_THROW(countHotBlocks(a, a, -2, 1.0), std::invalid_argument);
    EXPECT_EQ(countHotBlocks(a, a, 2, 0.0), 0);
}

TEST(ImageDiff, MeanAbsoluteDifferenceAveragesAllChannels) {
    Pair p;
    // |diffs| summed: 1 + 2 + 3 + (10 + 1) + 255 = 272 over 4 * 2 * 3 = 24 values.
    EXPECT_DOUBLE_EQ(meanAbsDifference(p.a, p.b), 272.0 / 24.0);
    EXPECT_DOUBLE_EQ(meanAbsDifference(p.b, p.a), 272.0 / 24.0);
    EXPECT_DOUBLE_EQ(meanAbsDifference(p.a, p.a), 0.0);
    EXPECT_DOUBLE_EQ(meanAbsDifference(filled(0, 0, 0), filled(0, 0, 0)), 0.0);
}

// ---- Float images: compareFilms (imgdiff --blocks) ----

Film filledFilm(int w, int h, const Vec3& c) {
    Film f(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) f.at(x, y) = c;
    return f;
}

/// Multiplies the pixels of [x0, x1) x [y0, y1) by `k`.
void scaleRect(Film& f, int x0, int y0, int x1, int y1, const Vec3& k) {
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) f.at(x, y) = f.at(x, y) * k;
}

TEST(FilmComparison, RelativeDifferenceIsAgainstTheReference) {
    EXPECT_NEAR(relativeDifference(1.02, 1.0), 0.02, 1e-15);
    EXPECT_NEAR(relativeDifference(0.98, 1.0), 0.02, 1e-15);
    EXPECT_NEAR(relativeDifference(1.0, 1.02), 0.02 / 1.02, 1e-15);
    EXPECT_EQ(relativeDifference(-3.0, -2.0), 0.5);
    EXPECT_EQ(relativeDifference(0.0, 0.0), 0.0);
    EXPECT_EQ(relativeDifference(1e-9, 0.0), std::numeric_limits<double>::infinity());
    EXPECT_TRUE(std::isnan(relativeDifference(std::nan(""), 1.0)));
    EXPECT_TRUE(std::isnan(relativeDifference(1.0, std::nan(""))));
}

TEST(FilmComparison, IdenticalImagesGiveZeroEverywhere) {
    Film a = filledFilm(40, 24, {0.5, 0.25, 0.125});
    a.at(3, 5) = {7, 0, 2};
    FilmComparison r = compareFilms(a, a, 16);
    EXPECT_EQ(r.blocks, 3 * 2);
    for (int c = 0; c < 4; ++c) {
        EXPECT_EQ(r.meanRel[c], 0.0);
        EXPECT_EQ(r.rmse[c], 0.0);
        EXPECT_EQ(r.meanA[c], r.meanB[c]);
    }
    EXPECT_EQ(r.worstLuminance.rel, 0.0);
    EXPECT_EQ(r.worstChannel.rel, 0.0);
}

TEST(FilmComparison, AKnownDifferenceInOneBlock) {
    // 64 x 48: 4 x 3 blocks of 16. Block (1, 2) of A is 2% brighter than the reference's.
    Film b = filledFilm(64, 48, {0.5, 0.25, 0.125});
    Film a = b;
    scaleRect(a, 16, 32, 32, 48, Vec3(1.02));
    FilmComparison r = compareFilms(a, b, 16);
    EXPECT_EQ(r.blocks, 12);
    EXPECT_NEAR(r.worstLuminance.rel, 0.02, 1e-12);
    EXPECT_EQ(r.worstLuminance.x, 16);
    EXPECT_EQ(r.worstLuminance.y, 32);
    EXPECT_EQ(r.worstLuminance.channel, -1);
    EXPECT_NEAR(r.worstChannel.rel, 0.02, 1e-12);
    EXPECT_EQ(r.worstChannel.x, 16);
    EXPECT_EQ(r.worstChannel.y, 32);
    // One block of twelve: the image means differ by a twelfth of that.
    for (int c = 0; c < 4; ++c) EXPECT_NEAR(r.meanRel[c], 0.02 / 12, 1e-12) << c;
    EXPECT_NEAR(r.meanB[3], 0.2126 * 0.5 + 0.7152 * 0.25 + 0.0722 * 0.125, 1e-15);
    // RMSE: 256 of 3072 pixels differ by 2% of the value.
    EXPECT_NEAR(r.rmse[0], 0.01 * std::sqrt(256.0 / 3072.0), 1e-12);
    // With the reference's block 2% brighter instead, the difference is 0.02 / 1.02.
    FilmComparison s = compareFilms(b, a, 16);
    EXPECT_NEAR(s.worstLuminance.rel, 0.02 / 1.02, 1e-12);
}

TEST(FilmComparison, ChannelsAndLuminanceAreReportedApart) {
    // Blue +10% in block (0, 0), green +1% in block (1, 0): luminance is led by green
    // (0.7152 * 0.01 * 0.25 against 0.0722 * 0.1 * 0.125 of the block's mean), the channels by
    // blue.
    Film b = filledFilm(32, 16, {0.5, 0.25, 0.125});
    Film a = b;
    scaleRect(a, 0, 0, 16, 16, {1, 1, 1.1});
    scaleRect(a, 16, 0, 32, 16, {1, 1.01, 1});
    FilmComparison r = compareFilms(a, b, 16);
    EXPECT_NEAR(r.worstChannel.rel, 0.1, 1e-12);
    EXPECT_EQ(r.worstChannel.channel, 2);
    EXPECT_EQ(r.worstChannel.x, 0);
    double lum = 0.2126 * 0.5 + 0.7152 * 0.25 + 0.0722 * 0.125;
    EXPECT_NEAR(r.worstLuminance.rel, 0.7152 * 0.0025 / lum, 1e-12);
    EXPECT_EQ(r.worstLuminance.x, 16);
}

TEST(FilmComparison, RmseOfAConstantOffset) {
    Film b = filledFilm(10, 10, {0.5, 0.25, 0.125});
    Film a = filledFilm(10, 10, {0.6, 0.35, 0.225});
    FilmComparison r = compareFilms(a, b, 4);
    for (int c = 0; c < 4; ++c) EXPECT_NEAR(r.rmse[c], 0.1, 1e-12) << c;  // weights sum to 1
}

TEST(FilmComparison, EdgeBlocksAreSmallerAndCounted) {
    // 20 x 20 in blocks of 16: one full block, two strips and a 4 x 4 corner. Only the corner
    // differs, by 50%: a partial block is compared by its own mean.
    Film b = filledFilm(20, 20, Vec3(1));
    Film a = b;
    scaleRect(a, 16, 16, 20, 20, Vec3(1.5));
    FilmComparison r = compareFilms(a, b, 16);
    EXPECT_EQ(r.blocks, 4);
    EXPECT_NEAR(r.worstLuminance.rel, 0.5, 1e-12);
    EXPECT_EQ(r.worstLuminance.x, 16);
    EXPECT_EQ(r.worstLuminance.y, 16);
    EXPECT_NEAR(r.meanRel[3], 0.5 * 16 / 400, 1e-12);
}

TEST(FilmComparison, NanAndZeroReferencesShow) {
    Film b = filledFilm(8, 8, Vec3(1));
    Film a = b;
    a.at(5, 5).y = std::nan("");
    FilmComparison r = compareFilms(a, b, 4);
    EXPECT_TRUE(std::isnan(r.meanRel[1]));
    EXPECT_TRUE(std::isnan(r.meanRel[3]));
    EXPECT_EQ(r.meanRel[0], 0.0);
    EXPECT_TRUE(std::isnan(r.worstLuminance.rel));
    EXPECT_EQ(r.worstLuminance.x, 4);
    // A black reference block that A is not black in: infinitely different.
    Film black = filledFilm(8, 8, Vec3(0));
    Film lit = black;
    lit.at(0, 0) = Vec3(0.1);
    EXPECT_EQ(compareFilms(lit, black, 4).worstLuminance.rel,
              std::numeric_limits<double>::infinity());
    EXPECT_EQ(compareFilms(black, black, 4).worstLuminance.rel, 0.0);
}

TEST(FilmComparison, SizesMustMatchAndBlocksBePositive) {
    Film a = filledFilm(8, 8, Vec3(1)), b = filledFilm(8, 9, Vec3(1));
    EXPECT_THROW(compareFilms(a, b, 4), std::invalid_argument);
    EXPECT_THROW(compareFilms(a, a, 0), std::invalid_argument);
    EXPECT_EQ(compareFilms(a, a, 100).blocks, 1);
}

// --- SSIM ------------------------------------------------------------------------------------

constexpr int kW = 48, kH = 40;

/// A grey test image with structure at several scales: smooth waves plus texel noise, in
/// [0.1, 0.9].
std::vector<double> textured(uint64_t seed = 1) {
    Rng rng(seed);
    std::vector<double> v(kW * kH);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x)
            v[y * kW + x] =
                0.5 + 0.2 * std::sin(x * 0.4) * std::cos(y * 0.3) + 0.2 * (rng.uniform() - 0.5);
    return v;
}

std::vector<double> plusNoise(const std::vector<double>& v, double amplitude) {
    Rng rng(99);
    std::vector<double> out = v;
    for (double& x : out) x += amplitude * (rng.uniform() - 0.5);
    return out;
}

/// A box blur of radius r (clamped at the edges).
std::vector<double> blurred(const std::vector<double>& v, int r) {
    std::vector<double> out(v.size());
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            double sum = 0;
            int n = 0;
            for (int dy = -r; dy <= r; ++dy)
                for (int dx = -r; dx <= r; ++dx) {
                    int xx = std::clamp(x + dx, 0, kW - 1), yy = std::clamp(y + dy, 0, kH - 1);
                    sum += v[yy * kW + xx];
                    ++n;
                }
            out[y * kW + x] = sum / n;
        }
    return out;
}

TEST(Ssim, EqualImagesScoreOne) {
    std::vector<double> x = textured();
    SsimResult r = ssim(x, x, kW, kH);
    EXPECT_NEAR(r.mean, 1.0, 1e-12);
    EXPECT_NEAR(r.lowest, 1.0, 1e-12);
    EXPECT_EQ(r.windows, (kW - 10) * (kH - 10));
    // Flat images too: the constants keep 0 / 0 away.
    std::vector<double> flat(kW * kH, 0.0);
    EXPECT_DOUBLE_EQ(ssim(flat, flat, kW, kH).mean, 1.0);
}

TEST(Ssim, IsSymmetric) {
    std::vector<double> x = textured(1), y = plusNoise(blurred(textured(1), 1), 0.1);
    SsimResult xy = ssim(x, y, kW, kH), yx = ssim(y, x, kW, kH);
    EXPECT_NEAR(xy.mean, yx.mean, 1e-12);
    EXPECT_NEAR(xy.lowest, yx.lowest, 1e-12);
    EXPECT_LT(xy.mean, 0.99);
}

TEST(Ssim, FallsAsNoiseGrows) {
    std::vector<double> x = textured();
    double previous = 1;
    for (double amplitude : {0.02, 0.05, 0.1, 0.3}) {
        double s = ssim(x, plusNoise(x, amplitude), kW, kH).mean;
        EXPECT_LT(s, previous) << "noise amplitude " << amplitude;
        previous = s;
    }
    EXPECT_LT(previous, 0.7);
}

TEST(Ssim, FallsAsBlurGrows) {
    std::vector<double> x = textured();
    double s1 = ssim(x, blurred(x, 1), kW, kH).mean, s2 = ssim(x, blurred(x, 2), kW, kH).mean;
    EXPECT_LT(s1, 0.95);
    EXPECT_LT(s2, s1);
    // Blur keeps the local means: the luminance term stays near 1, structure is what falls.
    EXPECT_GT(s2, 0);
}

TEST(Ssim, FlatImagesScoreTheirLuminanceTerm) {
    // Equal variances (0) leave (2 mu_x mu_y + C1) / (mu_x^2 + mu_y^2 + C1), eq. 13.
    std::vector<double> x(kW * kH, 0.2), y(kW * kH, 0.4);
    const double c1 = 0.01 * 0.01;
    const double expected = (2 * 0.2 * 0.4 + c1) / (0.2 * 0.2 + 0.4 * 0.4 + c1);
    EXPECT_NEAR(ssim(x, y, kW, kH).mean, expected, 1e-12);
    EXPECT_NEAR(ssim(x, y, kW, kH).lowest, expected, 1e-12);
}

TEST(Ssim, ScalesWithTheDynamicRange) {
    // C1 and C2 grow with L^2 as means and variances do with the values: scaling both changes
    // nothing.
    std::vector<double> x = textured(3), y = plusNoise(x, 0.2), x255 = x, y255 = y;
    for (double& v : x255) v *= 255;
    for (double& v : y255) v *= 255;
    EXPECT_NEAR(ssim(x, y, kW, kH).mean, ssim(x255, y255, kW, kH, 255).mean, 1e-9);
    // Larger constants forgive more: the same values score higher with L = 255 than L = 1.
    EXPECT_GT(ssim(x255, y255, kW, kH, 255).mean, ssim(x255, y255, kW, kH, 1).mean);
}

TEST(Ssim, InvertedContrastIsNegative) {
    std::vector<double> x = textured(), y = x;
    for (double& v : y) v = 1 - v;  // the same local means near 0.5, structure inverted
    EXPECT_LT(ssim(x, y, kW, kH).mean, -0.5);
}

TEST(Ssim, FindsTheLowestWindow) {
    std::vector<double> x = textured(), y = x;
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) y[(20 + dy) * kW + 30 + dx] += 0.5;
    SsimResult r = ssim(x, y, kW, kH);
    // The windows that see the change at all are within 5 pixels of it; the lowest is close.
    EXPECT_NEAR(r.lowestX, 30, 3);
    EXPECT_NEAR(r.lowestY, 20, 3);
    EXPECT_LT(r.lowest, 0.8);
    EXPECT_GT(r.mean, r.lowest);
}

TEST(Ssim, RejectsSmallOrMismatchedImages) {
    std::vector<double> small(10 * 40, 0.5), x = textured();
    EXPECT_THROW(ssim(small, small, 10, 40), std::invalid_argument);
    EXPECT_THROW(ssim(x, small, kW, kH), std::invalid_argument);
    EXPECT_THROW(ssim(x, x, kW, kH, 0), std::invalid_argument);
}

TEST(Ssim, DisplayLumaIsTheSrgbEncodedPreview) {
    Film f(4, 1);
    f.at(0, 0) = Vec3(1);
    f.at(1, 0) = Vec3(0);
    f.at(2, 0) = Vec3(0.5, 0.5, 0.5);
    f.at(3, 0) = Vec3(7, std::nan(""), 0);  // clamped; NaN counts as 0
    std::vector<double> y = displayLuma(f);
    EXPECT_DOUBLE_EQ(y[0], 1.0);
    EXPECT_DOUBLE_EQ(y[1], 0.0);
    EXPECT_NEAR(y[2], 0.735357, 1e-6);  // sRGB's 0.5 linear
    EXPECT_NEAR(y[3], 0.2126, 1e-12);
    EXPECT_NEAR(displayLuma(f, 1)[2], 1.0, 1e-12);  // 2^1 x 0.5
}

TEST(Ssim, DifferenceImageIsRedWhereBrighterBlueWhereDarker) {
    Film b = filledFilm(3, 1, Vec3(0.5)), a = b;
    a.at(0, 0) = Vec3(0.6);  // brighter by 0.1 = 0.2 x the mean
    a.at(1, 0) = Vec3(0.0);  // darker by 0.5: beyond the scale, clamped
    Film d = differenceImage(a, b, 0.4);
    EXPECT_NEAR(d.at(0, 0).x, 0.5, 1e-9);
    EXPECT_EQ(d.at(0, 0).z, 0.0);
    EXPECT_NEAR(d.at(1, 0).z, 1.0, 1e-12);
    EXPECT_EQ(d.at(1, 0).x, 0.0);
    EXPECT_EQ(d.at(2, 0), Vec3(0));
    EXPECT_THROW(differenceImage(a, filledFilm(2, 1, Vec3(1)), 0.4), std::invalid_argument);
    EXPECT_THROW(differenceImage(a, b, 0), std::invalid_argument);
}

}  // namespace
}  // namespace glint
