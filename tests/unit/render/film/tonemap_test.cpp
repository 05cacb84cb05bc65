// The Khronos PBR Neutral tone mapper (render/film/tonemap.h): the properties its specification
// documents, checked on many colours rather than on values copied from it.

#include "glint/render/film/tonemap.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "glint/math/rng.h"
#include "glint/render/film/display.h"

namespace glint {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

double maxOf(const Vec3& c) { return std::max({c.x, c.y, c.z}); }
double minOf(const Vec3& c) { return std::min({c.x, c.y, c.z}); }

/// HSV hue in turns [0, 1) of a colour whose channels differ (written here from the HSV
/// definition, independently of the tone mapper).
double hue(const Vec3& c) {
    const double hi = maxOf(c), lo = minOf(c), chroma = hi - lo;
    double h;
    if (hi == c.x)
        h = (c.y - c.z) / chroma;
    else if (hi == c.y)
        h = 2 + (c.z - c.x) / chroma;
    else
        h = 4 + (c.x - c.y) / chroma;
    h /= 6;
    return h - std::floor(h);
}

/// A random colour whose channels lie in [lo, hi), scaled by a random power of ten from
/// 10^minExp to 10^maxExp.
Vec3 randomColour(Rng& rng, double lo = 0, double hi = 1, int minExp = 0, int maxExp = 0) {
    double scale = std::pow(10.0, minExp + (maxExp - minExp) * static_cast<double>(rng.uniform()));
    auto channel = [&] { return (lo + (hi - lo) * static_cast<double>(rng.uniform())) * scale; };
    double r = channel(), g = channel(), b = channel();
    return {r, g, b};
}

TEST(PbrNeutral, BelowTheStartOfCompressionAColourLosesOnlyTheFresnelOffset) {
    // Colours with every channel at least 0.08 and the largest below 0.76 + 0.04: the 4% a
    // dielectric's specular reflection adds is taken away, nothing else changes. So a base
    // colour c under unit white light (c + 0.04 in the image) shows as c.
    Rng rng(1);
    for (int i = 0; i < 10000; ++i) {
        Vec3 c = randomColour(rng, 0.08, kPbrNeutralStartCompression + 0.04);
        Vec3 out = pbrNeutral(c);
        EXPECT_NEAR(out.x, c.x - 0.04, 1e-15);
        EXPECT_NEAR(out.y, c.y - 0.04, 1e-15);
        EXPECT_NEAR(out.z, c.z - 0.04, 1e-15);
    }
    EXPECT_NEAR(pbrNeutral(Vec3(0.54)).x, 0.5, 1e-15);
}

TEST(PbrNeutral, DarkColoursKeepBlackAndASmoothToe) {
    EXPECT_EQ(pbrNeutral(Vec3(0)), Vec3(0));
    // Below 0.08 the smallest channel x is lowered by x - 6.25 x^2: to 6.25 x^2, and every
    // other channel by the same amount.
    Rng rng(2);
    for (int i = 0; i < 1000; ++i) {
        Vec3 c = randomColour(rng, 0, 0.5);
        double x = minOf(c);
        if (x >= 0.08) continue;
        Vec3 out = pbrNeutral(c);
        double offset = x - 6.25 * x * x;
        EXPECT_NEAR(minOf(out), 6.25 * x * x, 1e-15);
        EXPECT_NEAR(out.x, c.x - offset, 1e-15);
        EXPECT_NEAR(out.z, c.z - offset, 1e-15);
    }
    // The offset is continuous, with a continuous slope, where the toe ends (x = 0.08).
    const double h = 1e-6;
    double below = pbrNeutral(Vec3(0.08 - h)).x, at = pbrNeutral(Vec3(0.08)).x,
           above = pbrNeutral(Vec3(0.08 + h)).x;
    EXPECT_NEAR(at, 0.04, 1e-15);
    EXPECT_NEAR(above - at, at - below, 1e-10);  // the same slope on both sides
    EXPECT_NEAR(above - at, h, 1e-10);           // 1: a grey above the toe moves as its input
}

TEST(PbrNeutral, MapsEveryInputIntoTheUnitRange) {
    Rng rng(3);
    for (int i = 0; i < 100000; ++i) {
        Vec3 out = pbrNeutral(randomColour(rng, 0, 1, -6, 6));
        EXPECT_GE(minOf(out), 0);
        EXPECT_LE(maxOf(out), 1);
    }
    // Whatever a film may hold: negative, NaN and infinite radiance too.
    for (Vec3 c : {Vec3(-1, 0.5, 2), Vec3(kNaN, 0.2, 0.3), Vec3(kInf), Vec3(kInf, 0, 0),
                   Vec3(-kInf, kNaN, 1e300), Vec3(1e30, 1e-30, 0)}) {
        Vec3 out = pbrNeutral(c);
        for (double v : {out.x, out.y, out.z}) {
            EXPECT_TRUE(v >= 0 && v <= 1) << c.x << " " << c.y << " " << c.z << " -> " << v;
        }
    }
    // Very bright light tends to white.
    EXPECT_GT(minOf(pbrNeutral(Vec3(1e6, 2e5, 5e4))), 0.999);
}

TEST(PbrNeutral, KeepsTheHueOfEveryColour) {
    // Every step adds the same amount to all channels or scales them alike: the HSV hue is
    // unchanged, in the compressed range too, while the colour keeps some chroma.
    Rng rng(4);
    int compared = 0, compressed = 0;
    for (int i = 0; i < 20000; ++i) {
        Vec3 c = randomColour(rng, 0, 1, -2, 2);
        Vec3 out = pbrNeutral(c);
        if (maxOf(c) - minOf(c) < 1e-3 * maxOf(c) || maxOf(out) - minOf(out) < 1e-9) continue;
        double d = std::abs(hue(out) - hue(c));
        EXPECT_LT(std::min(d, 1 - d), 1e-6) << c.x << " " << c.y << " " << c.z;
        ++compared;
        compressed += maxOf(c) > 1;
    }
    EXPECT_GT(compared, 15000);
    EXPECT_GT(compressed, 5000);  // the compression and the desaturation were exercised
}

TEST(PbrNeutral, IsMonotonicInBrightness) {
    // A colour made brighter never maps darker, in any channel; its largest channel rises
    // strictly until it saturates.
    Rng rng(5);
    for (int i = 0; i < 2000; ++i) {
        Vec3 c = randomColour(rng);
        Vec3 previous = pbrNeutral(c * 1e-4);
        for (double k = 1.1e-4; k < 1e4; k *= 1.1) {
            Vec3 out = pbrNeutral(c * k);
            EXPECT_GE(out.x, previous.x - 1e-15) << k;
            EXPECT_GE(out.y, previous.y - 1e-15) << k;
            EXPECT_GE(out.z, previous.z - 1e-15) << k;
            if (maxOf(previous) < 0.999) {
                EXPECT_GT(maxOf(out), maxOf(previous)) << k;
            }
            previous = out;
        }
    }
}

TEST(PbrNeutral, IsContinuousWhereCompressionStarts) {
    // Value and slope agree on both sides of the start of compression (peak 0.76 after the
    // offset): the compressed peak 1 - d^2 / (p + d - s) has slope 1 at p = s.
    for (Vec3 hueOf : {Vec3(1), Vec3(1, 0.5, 0.25), Vec3(0.2, 1, 0.6)}) {
        Vec3 at = hueOf * (kPbrNeutralStartCompression / maxOf(hueOf));
        at = at + Vec3(0.04);  // the offset is 0.04 where every channel is above 0.08
        const double h = 1e-6;
        Vec3 below = pbrNeutral(at - Vec3(h)), mid = pbrNeutral(at),
             above = pbrNeutral(at + Vec3(h));
        EXPECT_NEAR(maxOf(above) - maxOf(mid), maxOf(mid) - maxOf(below), 1e-10);
        EXPECT_NEAR(maxOf(above) - maxOf(below), 2 * h, 1e-10);
    }
}

TEST(PbrNeutral, KeepsGreysGrey) {
    for (double v : {0.0, 0.01, 0.1, 0.5, 0.76, 0.8, 1.0, 3.0, 100.0}) {
        Vec3 out = pbrNeutral(Vec3(v));
        EXPECT_EQ(out.x, out.y);
        EXPECT_EQ(out.y, out.z);
    }
}

TEST(ToneMap, ClampClampsEachChannel) {
    EXPECT_EQ(toneMap(ToneMap::Clamp, Vec3(-1, 0.5, 7)), Vec3(0, 0.5, 1));
    EXPECT_EQ(toneMap(ToneMap::Clamp, Vec3(kNaN, 1, 0)), Vec3(0, 1, 0));
    EXPECT_EQ(toneMap(ToneMap::PbrNeutral, Vec3(0.3, 2, 5)), pbrNeutral(Vec3(0.3, 2, 5)));
    EXPECT_EQ(toneMapNamed("neutral"), ToneMap::PbrNeutral);
    EXPECT_EQ(toneMapNamed("clamp"), ToneMap::Clamp);
    EXPECT_EQ(toneMapNamed("aces"), ToneMap::Aces);
    EXPECT_FALSE(toneMapNamed("filmic"));
    for (ToneMap t : {ToneMap::Clamp, ToneMap::PbrNeutral, ToneMap::Aces})
        EXPECT_EQ(toneMapNamed(toneMapName(t)), t);
    EXPECT_EQ(toneMap(ToneMap::Aces, Vec3(0.3, 2, 5)), acesFilmic(Vec3(0.3, 2, 5)));
}

/// Hill's rational fit of the ACES curve, on one channel (after the 1/0.6 boost).
double acesFit(double v) {
    return (v * (v + 0.0245786) - 0.000090537) / (v * (0.983729 * v + 0.4329510) + 0.238081);
}

TEST(AcesFilmic, GreysStayGreyAndFollowTheFitOfTheBoostedValue) {
    // Both matrices keep (1, 1, 1): their rows sum to 1 (to the five decimals published).
    for (double v : {0.05, 0.18, 0.5, 1.0, 2.0, 8.0}) {
        Vec3 out = acesFilmic(Vec3(v));
        EXPECT_NEAR(out.x, acesFit(v / 0.6), 2e-5) << v;
        EXPECT_NEAR(out.y, out.x, 2e-5);
        EXPECT_NEAR(out.z, out.x, 2e-5);
    }
    EXPECT_EQ(acesFilmic(Vec3(0)), Vec3(0));  // the fit's small negative value, clamped
}

TEST(AcesFilmic, StaysInRangeRisesWithRadianceAndReadsBadValuesSafely) {
    double last = -1;
    for (double v = 0; v < 1000; v = v * 1.3 + 0.01) {
        Vec3 out = acesFilmic(Vec3(v, 0.5 * v, 0.1 * v));
        for (double c : {out.x, out.y, out.z}) {
            EXPECT_GE(c, 0);
            EXPECT_LE(c, 1);
        }
        EXPECT_GE(out.x, last);
        last = out.x;
    }
    EXPECT_GT(acesFilmic(Vec3(1e6)).x, 0.99);
    Vec3 bad = acesFilmic(Vec3(kNaN, -3, std::numeric_limits<double>::infinity()));
    for (double c : {bad.x, bad.y, bad.z}) EXPECT_TRUE(c >= 0 && c <= 1);
    // A saturated colour keeps its dominant channel.
    Vec3 red = acesFilmic(Vec3(0.8, 0.1, 0.05));
    EXPECT_GT(red.x, red.y);
    EXPECT_GT(red.y, red.z - 1e-9);
}

TEST(ToneMap, EightBitImagesGoThroughTheExposureTheToneMapperAndTheCurve) {
    Film film(3, 1);
    film.at(0, 0) = {0.2, 0.5, 0.9};
    film.at(1, 0) = {3, 1.5, 0.1};
    film.at(2, 0) = {40, 40, 40};
    DisplayTransform display;
    display.toneMap = ToneMap::PbrNeutral;
    display.srgb = true;
    display.exposure = 1;
    EXPECT_FALSE(display.isIdentity());
    Image8 img = toImage8(film, display);
    for (int x = 0; x < 3; ++x) {
        Vec3 expected = pbrNeutral(film.at(x, 0) * 2.0);
        EXPECT_EQ(img.at(x, 0, 0), toByteSrgb(expected.x));
        EXPECT_EQ(img.at(x, 0, 1), toByteSrgb(expected.y));
        EXPECT_EQ(img.at(x, 0, 2), toByteSrgb(expected.z));
    }
    // Without the curve, the course's floor of the tone-mapped value.
    display.srgb = false;
    img = toImage8(film, display);
    EXPECT_EQ(img.at(1, 0, 0), toByte(pbrNeutral(film.at(1, 0) * 2.0).x));
    EXPECT_LT(img.at(2, 0, 0), 255);  // compressed, not clipped
}

}  // namespace
}  // namespace glint
