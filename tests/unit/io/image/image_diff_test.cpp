#include "glint/io/image/image_diff.h"

#include <gtest/gtest.h>

#include <stdexcept>

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

}  // namespace
}  // namespace glint
