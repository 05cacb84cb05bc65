#include "glint/render/film/display.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace glint {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

/// The inverse of the sRGB curve (IEC 61966-2-1), written independently of srgbEncode.
double srgbDecode(double v) {
    return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
}

/// A 4 x 2 film with values inside and outside [0, 1].
Film testFilm() {
    Film f(4, 2);
    const double v[8][3] = {{0.7, 1.0, 0.999}, {-0.5, 1.5, 0.5},  {0.25, 0.0, 2.0},
                            {0.1, 0.2, 0.3},   {kNaN, 0.9, 1e9},  {0.004, 0.996, -1e9},
                            {1e-5, 0.02, 0.6}, {0.125, 0.0625, 8}};
    for (int i = 0; i < 8; ++i) f.at(i % 4, i / 4) = {v[i][0], v[i][1], v[i][2]};
    return f;
}

// ---- the sRGB curve ---------------------------------------------------------------------

TEST(SrgbEncode, KnownPoints) {
    EXPECT_EQ(srgbEncode(0.0), 0.0);
    EXPECT_EQ(srgbEncode(1.0), 1.0);
    EXPECT_NEAR(srgbEncode(0.5), 0.735356983, 1e-9);   // 1.055 * 0.5^(1/2.4) - 0.055
    EXPECT_NEAR(srgbEncode(0.18), 0.461356129, 1e-9);  // photographic mid grey
    EXPECT_NEAR(srgbEncode(0.214041140), 0.5, 1e-9);
}

TEST(SrgbEncode, IsTheLinearSegmentBelowTheThreshold) {
    for (double c : {1e-12, 1e-6, 0.001, 0.002, 0.003, 0.0031308})
        EXPECT_DOUBLE_EQ(srgbEncode(c), 12.92 * c) << c;
    // Just above the threshold, the power segment; the two meet within 1e-7 there.
    EXPECT_NEAR(srgbEncode(0.0031309), 1.055 * std::pow(0.0031309, 1 / 2.4) - 0.055, 1e-15);
    EXPECT_NEAR(srgbEncode(0.0031309), 12.92 * 0.0031309, 1e-7);
}

TEST(SrgbEncode, ClampsOutOfRangeValuesAndNaN) {
    EXPECT_EQ(srgbEncode(-0.1), 0.0);
    EXPECT_EQ(srgbEncode(-kInf), 0.0);
    EXPECT_EQ(srgbEncode(kNaN), 0.0);
    EXPECT_EQ(srgbEncode(1.0001), 1.0);
    EXPECT_EQ(srgbEncode(kInf), 1.0);
}

TEST(SrgbEncode, IsMonotonicAndNeverDarkerThanLinear) {
    double last = 0;
    for (int i = 0; i <= 100000; ++i) {
        double c = i / 100000.0;
        double v = srgbEncode(c);
        ASSERT_GE(v, last) << c;
        ASSERT_GE(v, c) << c;
        last = v;
    }
}

TEST(SrgbByte, RoundsTheEncodedValue) {
    EXPECT_EQ(toByteSrgb(0.0), 0);
    EXPECT_EQ(toByteSrgb(0.5), 188);  // 255 * 0.73536 = 187.52: rounds up (floor gives 187)
    EXPECT_EQ(toByteSrgb(1.0), 255);
    EXPECT_EQ(toByteSrgb(0.001), 3);   // 255 * 0.01292 = 3.29, on the linear segment
    EXPECT_EQ(toByteSrgb(0.0001), 0);  // 0.33 rounds down
    EXPECT_EQ(toByteSrgb(0.0002), 1);  // 0.66 rounds up
    EXPECT_EQ(toByteSrgb(7.0), 255);
    EXPECT_EQ(toByteSrgb(-1.0), 0);
    EXPECT_EQ(toByteSrgb(kNaN), 0);
}

TEST(SrgbByte, EveryLevelRoundTripsThroughTheInverseCurve) {
    // Decoding level k to linear and encoding it again gives k: the rounding is to nearest.
    for (int k = 0; k <= 255; ++k) EXPECT_EQ(toByteSrgb(srgbDecode(k / 255.0)), k) << k;
}

// ---- exposure and the 8-bit conversion ----------------------------------------------------

TEST(DisplayTransform, ScaleIsTwoToTheExposure) {
    EXPECT_EQ(DisplayTransform{}.scale(), 1.0);
    EXPECT_EQ(DisplayTransform{1}.scale(), 2.0);
    EXPECT_EQ(DisplayTransform{3}.scale(), 8.0);
    EXPECT_EQ(DisplayTransform{-2}.scale(), 0.25);
    EXPECT_NEAR(DisplayTransform{0.5}.scale(), std::sqrt(2.0), 1e-15);
    EXPECT_TRUE(DisplayTransform{}.isIdentity());
    EXPECT_FALSE((DisplayTransform{0, true}.isIdentity()));
    EXPECT_FALSE(DisplayTransform{-1}.isIdentity());
}

TEST(DisplayTransform, DefaultIsTheCoursesConversionByteForByte) {
    Film f = testFilm();
    EXPECT_EQ(toImage8(f, DisplayTransform{}).data, toImage8(f).data);
}

TEST(DisplayTransform, EachEvDoublesTheValueBeforeTheCoursesFloor) {
    Film f(3, 1);
    f.at(0, 0) = {0.25, 0.1, 0.3};
    f.at(1, 0) = {0.5, 1.0, 0.0};
    f.at(2, 0) = {0.0625, 0.7, 2.0};
    for (double ev : {-3.0, -1.0, 1.0, 2.0}) {
        Image8 img = toImage8(f, DisplayTransform{ev});
        const double s = std::exp2(ev);
        size_t i = 0;
        for (int x = 0; x < 3; ++x)
            for (int c = 0; c < 3; ++c) EXPECT_EQ(img.data[i++], toByte(s * f.at(x, 0)[c])) << ev;
    }
    // +1 EV: 0.25 -> 0.5 -> floor(127.5) = 127; 1.0 -> 2 -> 255. -1 EV: 1.0 -> 127.
    EXPECT_EQ(toImage8(f, DisplayTransform{1}).at(0, 0, 0), 127);
    EXPECT_EQ(toImage8(f, DisplayTransform{1}).at(1, 0, 1), 255);
    EXPECT_EQ(toImage8(f, DisplayTransform{-1}).at(1, 0, 1), 127);
    EXPECT_EQ(toImage8(f, DisplayTransform{2}).at(2, 0, 0), 63);  // 0.0625 * 4 = 0.25
}

TEST(DisplayTransform, SrgbAppliesTheCurveAfterTheExposure) {
    Film f(2, 1);
    f.at(0, 0) = {0.25, 0.5, 0.0};
    f.at(1, 0) = {kNaN, 3.0, -1.0};
    Image8 srgb = toImage8(f, DisplayTransform{0, true});
    EXPECT_EQ(srgb.at(0, 0, 0), toByteSrgb(0.25));
    EXPECT_EQ(srgb.at(0, 0, 1), 188);
    EXPECT_EQ(srgb.at(0, 0, 2), 0);
    EXPECT_EQ(srgb.at(1, 0, 0), 0);
    EXPECT_EQ(srgb.at(1, 0, 1), 255);
    EXPECT_EQ(srgb.at(1, 0, 2), 0);
    Image8 brighter = toImage8(f, DisplayTransform{1, true});
    EXPECT_EQ(brighter.at(0, 0, 0), 188);  // 0.25 * 2 = 0.5
    EXPECT_EQ(brighter.at(0, 0, 1), 255);
}

}  // namespace
}  // namespace glint
