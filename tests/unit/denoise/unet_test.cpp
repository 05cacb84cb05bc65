#include "glint/denoise/unet/unet.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "glint/denoise/unet/tza.h"
#include "glint/denoise/unet/unet_filter.h"
#include "glint/math/rng.h"

namespace glint {
namespace {

// Writes archives of version 2 as OIDN's weights files are laid out (tza.h), float32 or float16.
class ArchiveWriter {
  public:
    void add(const std::string& name, std::vector<int> dims, const std::string& layout,
             const std::vector<float>& values, bool half = false) {
        entries_.push_back({name, std::move(dims), layout, values, half});
    }
    std::vector<uint8_t> bytes(uint8_t major = 2) const {
        std::vector<uint8_t> out(16, 0);
        std::vector<uint64_t> offsets;
        for (const Entry& e : entries_) {
            while (out.size() % 64) out.push_back(0);
            offsets.push_back(out.size());
            for (float v : e.values) {
                if (e.half)
                    put<uint16_t>(out, toHalf(v));
                else {
                    uint32_t u;
                    std::memcpy(&u, &v, 4);
                    put(out, u);
                }
            }
        }
        const uint64_t table = out.size();
        put<uint32_t>(out, static_cast<uint32_t>(entries_.size()));
        for (size_t i = 0; i < entries_.size(); ++i) {
            const Entry& e = entries_[i];
            put<uint16_t>(out, static_cast<uint16_t>(e.name.size()));
            out.insert(out.end(), e.name.begin(), e.name.end());
            out.push_back(static_cast<uint8_t>(e.dims.size()));
            for (int d : e.dims) put<uint32_t>(out, static_cast<uint32_t>(d));
            out.insert(out.end(), e.layout.begin(), e.layout.end());
            out.push_back(e.half ? 'h' : 'f');
            put<uint64_t>(out, offsets[i]);
        }
        std::vector<uint8_t> header;
        put<uint16_t>(header, 0x41D7);
        header.push_back(major);
        header.push_back(0);
        put<uint64_t>(header, table);
        std::copy(header.begin(), header.end(), out.begin());
        return out;
    }

  private:
    struct Entry {
        std::string name;
        std::vector<int> dims;
        std::string layout;
        std::vector<float> values;
        bool half;
    };
    template <typename T>
    static void put(std::vector<uint8_t>& out, T v) {
        for (size_t i = 0; i < sizeof(T); ++i) out.push_back(static_cast<uint8_t>(v >> (8 * i)));
    }
    // Values the tests use are exact in half: sign, exponent and the top 10 mantissa bits.
    static uint16_t toHalf(float v) {
        uint32_t u;
        std::memcpy(&u, &v, 4);
        const uint32_t sign = (u >> 16) & 0x8000u;
        const int exponent = static_cast<int>((u >> 23) & 0xff) - 127 + 15;
        if ((u & 0x7fffffffu) == 0) return static_cast<uint16_t>(sign);
        return static_cast<uint16_t>(sign | static_cast<uint32_t>(exponent) << 10 |
                                     ((u >> 13) & 0x3ff));
    }
    std::vector<Entry> entries_;
};

std::string errorOf(const std::vector<uint8_t>& bytes) {
    try {
        parseTza(bytes, "w.tza");
    } catch (const std::runtime_error& e) {
        return e.what();
    }
    return "";
}

TEST(Tza, ReadsFloatAndHalfTensorsWithShapesAndLayouts) {
    ArchiveWriter w;
    w.add("conv.weight", {2, 1, 3, 3}, "oihw",
          {1, -2, 0.5f, 0.25f, 3, 4, 5, 6, 7, -1, -0.5f, 8, 9, 10, 11, 12, 13, 14});
    w.add("conv.bias", {2}, "x", {0.125f, -64}, /*half=*/true);
    const TzaTensors t = parseTza(w.bytes(), "w.tza");
    ASSERT_EQ(t.size(), 2u);
    const TzaTensor& weight = t.at("conv.weight");
    EXPECT_EQ(weight.dims, (std::vector<int>{2, 1, 3, 3}));
    EXPECT_EQ(weight.layout, "oihw");
    EXPECT_EQ(weight.values[1], -2.f);
    EXPECT_EQ(weight.values[17], 14.f);
    EXPECT_EQ(t.at("conv.bias").values, (std::vector<float>{0.125f, -64.f}));
}

TEST(Tza, HalfToFloatCoversEveryKindOfValue) {
    EXPECT_EQ(halfToFloat(0x3c00), 1.f);
    EXPECT_EQ(halfToFloat(0xc000), -2.f);
    EXPECT_EQ(halfToFloat(0x7bff), 65504.f);
    EXPECT_EQ(halfToFloat(0x0001), std::ldexp(1.f, -24));  // the smallest subnormal
    EXPECT_EQ(halfToFloat(0x03ff), std::ldexp(1023.f, -24));
    EXPECT_TRUE(std::signbit(halfToFloat(0x8000)));
    EXPECT_TRUE(std::isinf(halfToFloat(0x7c00)));
    EXPECT_TRUE(std::isnan(halfToFloat(0x7e00)));
}

TEST(Tza, RefusesWhatIsNotAWellFormedArchiveSayingWhy) {
    ArchiveWriter w;
    w.add("b", {3}, "x", {1, 2, 3});
    const std::vector<uint8_t> good = w.bytes();
    EXPECT_EQ(errorOf(good), "");

    EXPECT_NE(errorOf({0xD7}).find("ends inside the magic number"), std::string::npos);
    std::vector<uint8_t> bad = good;
    bad[0] = 'P';
    EXPECT_NE(errorOf(bad).find("w.tza: not an Open Image Denoise tensor archive"),
              std::string::npos);
    EXPECT_NE(errorOf(w.bytes(1)).find("version 1.0, where Glint reads version 2"),
              std::string::npos);
    // Cut anywhere: an error, never a read past the end.
    for (size_t n = 0; n < good.size(); ++n) {
        const std::vector<uint8_t> cut(good.begin(), good.begin() + static_cast<long>(n));
        EXPECT_NE(errorOf(cut), "") << n;
    }
    // The data offset moved past the end.
    bad = good;
    bad[bad.size() - 8] = 0xff;
    bad[bad.size() - 2] = 0x01;
    EXPECT_NE(errorOf(bad).find("tensor 'b' lies beyond its end"), std::string::npos);

    ArchiveWriter twice;
    twice.add("b", {1}, "x", {1});
    twice.add("b", {1}, "x", {2});
    EXPECT_NE(errorOf(twice.bytes()).find("appears twice"), std::string::npos);
    ArchiveWriter nan;
    nan.add("b", {1}, "x", {std::nanf("")});
    EXPECT_NE(errorOf(nan.bytes()).find("not finite"), std::string::npos);
}

TEST(Tza, ReadingAMissingFileSaysSo) {
    EXPECT_THROW(
        {
            try {
                readTza("/nonexistent/w.tza");
            } catch (const std::runtime_error& e) {
                EXPECT_STREQ(e.what(), "/nonexistent/w.tza: cannot read it");
                throw;
            }
        },
        std::runtime_error);
}

FeatureMap randomMap(int c, int h, int w, Rng& rng, float lo = -1, float hi = 1) {
    FeatureMap m(c, h, w);
    for (float& v : m.values) v = lo + (hi - lo) * static_cast<float>(rng.uniform());
    return m;
}

TEST(UNetLayers, ConvolutionIsTheSumOverTapsWithZerosOutsideThenRelu) {
    Rng rng(7);
    const FeatureMap in = randomMap(2, 5, 7, rng);
    Conv3x3 conv{"c", 2, 3, {}, {0.1f, -0.2f, 0.3f}};
    for (int i = 0; i < 3 * 2 * 9; ++i)
        conv.weights.push_back(static_cast<float>(rng.uniform()) - 0.5f);
    ThreadPool pool(2);
    const FeatureMap out = convolveRelu(conv, in, pool);
    ASSERT_EQ(out.channels, 3);
    int positive = 0, zero = 0;
    for (int o = 0; o < 3; ++o)
        for (int y = 0; y < 5; ++y)
            for (int x = 0; x < 7; ++x) {
                double sum = conv.bias[static_cast<size_t>(o)];
                for (int i = 0; i < 2; ++i)
                    for (int ky = 0; ky < 3; ++ky)
                        for (int kx = 0; kx < 3; ++kx) {
                            const int sy = y + ky - 1, sx = x + kx - 1;
                            if (sy < 0 || sy >= 5 || sx < 0 || sx >= 7) continue;
                            sum += double(conv.weights[static_cast<size_t>(
                                       ((o * 2 + i) * 3 + ky) * 3 + kx)]) *
                                   in.at(i, sy, sx);
                        }
                const double expected = std::max(sum, 0.0);
                EXPECT_NEAR(out.at(o, y, x), expected, 1e-5) << o << " " << y << " " << x;
                (expected > 0 ? positive : zero) += 1;
            }
    // Both sides of the ReLU were exercised.
    EXPECT_GT(positive, 10);
    EXPECT_GT(zero, 10);
}

TEST(UNetLayers, PoolTakesEachBlocksLargestAndUpsampleRepeatsEachValue) {
    FeatureMap in(1, 2, 4);
    in.values = {1,  -3,   0, 2,  //
                 -1, 0.5f, 7, -8};
    const FeatureMap pooled = maxPool2x2(in);
    ASSERT_EQ(pooled.width, 2);
    ASSERT_EQ(pooled.height, 1);
    EXPECT_EQ(pooled.values, (std::vector<float>{1, 7}));
    const FeatureMap up = upsample2x(pooled);
    EXPECT_EQ(up.values, (std::vector<float>{1, 1, 7, 7, 1, 1, 7, 7}));

    FeatureMap a(1, 1, 2), b(2, 1, 2);
    a.values = {1, 2};
    b.values = {3, 4, 5, 6};
    EXPECT_EQ(concatenate(a, b).values, (std::vector<float>{1, 2, 3, 4, 5, 6}));
    EXPECT_THROW(concatenate(a, FeatureMap(1, 2, 1)), std::invalid_argument);
}

// The tensors of a base-shaped U-Net (OIDN's layer names) with `width` channels per layer and
// weights `weight(layer, out, in, tap)`.
template <typename Weight>
TzaTensors baseNet(int inputs, int width, Weight weight) {
    TzaTensors t;
    auto conv = [&](const std::string& name, int in, int out) {
        TzaTensor w{{out, in, 3, 3}, "oihw", {}},
            b{{out}, "x", std::vector<float>(static_cast<size_t>(out), 0.f)};
        for (int o = 0; o < out; ++o)
            for (int i = 0; i < in; ++i)
                for (int tap = 0; tap < 9; ++tap) w.values.push_back(weight(name, o, i, tap));
        t[name + ".weight"] = w;
        t[name + ".bias"] = b;
    };
    conv("enc_conv0", inputs, width);
    for (const char* n :
         {"enc_conv1", "enc_conv2", "enc_conv3", "enc_conv4", "enc_conv5a", "enc_conv5b"})
        conv(n, width, width);
    for (const char* n : {"dec_conv4a", "dec_conv3a", "dec_conv2a"}) conv(n, 2 * width, width);
    for (const char* n : {"dec_conv4b", "dec_conv3b", "dec_conv2b"}) conv(n, width, width);
    conv("dec_conv1a", width + inputs, width);
    conv("dec_conv1b", width, width);
    conv("dec_conv0", width, 3);
    return t;
}

TEST(UNet, ReadsItsShapeFromTheLayerNamesAndCountsItsWork) {
    const UNet net =
        UNet::fromTensors(baseNet(9, 4, [](const std::string&, int, int, int) { return 0.f; }));
    EXPECT_EQ(net.inputChannels(), 9);
    EXPECT_EQ(net.outputChannels(), 3);
    // Weights and biases: enc_conv0 9 -> 4; six layers 4 -> 4; three joins 8 -> 4 and the
    // three layers after them; dec_conv1a 13 -> 4, dec_conv1b 4 -> 4, dec_conv0 4 -> 3.
    EXPECT_EQ(net.parameters(), (9 * 4 * 9 + 4) + 6 * (4 * 4 * 9 + 4) + 3 * (8 * 4 * 9 + 4) +
                                    3 * (4 * 4 * 9 + 4) + (13 * 4 * 9 + 4) + (4 * 4 * 9 + 4) +
                                    (4 * 3 * 9 + 3));
    // Full size: 324 + 144 + 468 + 144 + 108; half: 576 / 4; quarter: 576 / 16; an eighth:
    // 576 / 64; the bottom, a sixteenth: 288 / 256.
    EXPECT_DOUBLE_EQ(net.multiplyAddsPerPixel(), 1188 + 144 + 36 + 9 + 1.125);
}

TEST(UNet, SaysWhichLayerIsMissingOrDoesNotFit) {
    TzaTensors t = baseNet(9, 4, [](const std::string&, int, int, int) { return 0.f; });
    TzaTensors missing = t;
    missing.erase("dec_conv2b.weight");
    try {
        UNet::fromTensors(missing);
        FAIL() << "no error";
    } catch (const std::runtime_error& e) {
        EXPECT_STREQ(e.what(), "the weights have no layer 'dec_conv2b'");
    }
    TzaTensors misfit = t;
    misfit["enc_conv2.weight"].dims = {4, 5, 3, 3};
    misfit["enc_conv2.weight"].values.resize(4 * 5 * 9);
    try {
        UNet::fromTensors(misfit);
        FAIL() << "no error";
    } catch (const std::runtime_error& e) {
        EXPECT_STREQ(e.what(), "layer 'enc_conv2' takes 5 channels where the network gives it 4");
    }
}

TEST(UNet, AnIdentityPathThroughTheSkipsReturnsTheInput) {
    // Every layer passes its first channel on (centre tap 1) and the decoder's joins pass the
    // skip's first channel, so the output's channel 0 is the input's channel 0 (all >= 0): the
    // wiring of pools, upsampling and joins, checked end to end.
    auto weight = [](const std::string& name, int out, int in, int tap) -> float {
        if (tap != 4 || out != 0) return 0.f;
        return in == (name == "dec_conv1a" ? 4 : 0) ? 1.f : 0.f;  // there: the input's channel 0
    };
    const UNet net = UNet::fromTensors(baseNet(9, 4, weight));
    Rng rng(3);
    const FeatureMap in = randomMap(9, 32, 48, rng, 0, 1);
    ThreadPool pool(2);
    const FeatureMap out = net.run(in, pool);
    ASSERT_EQ(out.channels, 3);
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 48; ++x) {
            EXPECT_EQ(out.at(0, y, x), in.at(0, y, x));
            EXPECT_EQ(out.at(1, y, x), 0.f);
        }
    EXPECT_THROW(net.run(randomMap(9, 24, 48, rng), pool), std::invalid_argument);
}

TEST(UNetFilter, TransferFunctionRoundTripsAndExposureMapsTheKeyTo018) {
    for (float v : {0.f, 1e-7f, 1e-4f, 0.01f, 0.5f, 1.f, 30.f, 1000.f, 65504.f}) {
        const float y = puForward(v);
        EXPECT_GE(y, 0.f);
        EXPECT_LE(y, 1.0001f);
        EXPECT_NEAR(puInverse(y), v, 1e-4f * std::max(v, 1e-3f)) << v;
    }
    EXPECT_NEAR(puForward(65504.f), 1.f, 1e-6f);
    EXPECT_LT(puForward(0.1f), puForward(0.2f));

    std::vector<Vec3> grey(40 * 24, Vec3(2.5));
    EXPECT_NEAR(autoexposure(grey.data(), 40, 24), 0.18f / 2.5f, 1e-6f);
    std::vector<Vec3> black(40 * 24, Vec3(0.0));
    EXPECT_EQ(autoexposure(black.data(), 40, 24), 1.f);
}

}  // namespace
}  // namespace glint

namespace glint {
namespace {

// A base-shaped U-Net with these channels per layer (encoder levels 1 to 4, the bottom, decoder
// levels 4 to 1) and random weights: odd counts, so that tasks get one to four output blocks
// (the kernels' two-vector, one-vector and lone-block tiles) and joins padded blocks.
UNet randomNet(Rng& rng, int inputs) {
    const int enc[4] = {12, 20, 36, 40}, bottom = 28, dec[4] = {44, 24, 16, 8};
    TzaTensors t;
    auto conv = [&](const std::string& name, int in, int out) {
        TzaTensor w{{out, in, 3, 3}, "oihw", {}}, b{{out}, "x", {}};
        const double scale = std::sqrt(2.0 / (9 * in));
        for (int i = 0; i < out * in * 9; ++i)
            w.values.push_back(static_cast<float>(scale * (2 * rng.uniform() - 1) * 1.7));
        for (int o = 0; o < out; ++o)
            b.values.push_back(static_cast<float>(0.1 * (rng.uniform() - 0.5)));
        t[name + ".weight"] = w;
        t[name + ".bias"] = b;
    };
    conv("enc_conv0", inputs, enc[0]);
    conv("enc_conv1", enc[0], enc[0]);
    conv("enc_conv2", enc[0], enc[1]);
    conv("enc_conv3", enc[1], enc[2]);
    conv("enc_conv4", enc[2], enc[3]);
    conv("enc_conv5a", enc[3], bottom);
    conv("enc_conv5b", bottom, bottom);
    conv("dec_conv4a", bottom + enc[2], dec[0]);
    conv("dec_conv4b", dec[0], dec[0]);
    conv("dec_conv3a", dec[0] + enc[1], dec[1]);
    conv("dec_conv3b", dec[1], dec[1]);
    conv("dec_conv2a", dec[1] + enc[0], dec[2]);
    conv("dec_conv2b", dec[2], dec[2]);
    conv("dec_conv1a", dec[2] + inputs, dec[3]);
    conv("dec_conv1b", dec[3], dec[3]);
    conv("dec_conv0", dec[3], 3);
    return UNet::fromTensors(t);
}

std::vector<unet::KernelIsa> kernelsHere() {
    std::vector<unet::KernelIsa> out;
    for (unet::KernelIsa isa : {unet::KernelIsa::Portable, unet::KernelIsa::Avx2,
                                unet::KernelIsa::Avx512, unet::KernelIsa::Simd128})
        if (unet::runs(isa)) out.push_back(isa);
    return out;
}

float largestValue(const FeatureMap& m) {
    float top = 0;
    for (float v : m.values) top = std::max(top, std::fabs(v));
    return top;
}

TEST(UNetKernels, EveryKernelSetMatchesTheOracleOnOddSizes) {
    Rng rng(11);
    for (int inputs : {3, 9}) {
        const UNet net = randomNet(rng, inputs);
        // 80 wide: full-size rows end in partial tiles (12- and 6-pixel tiles), the bottom is 5.
        const FeatureMap in = randomMap(inputs, 48, 80, rng, 0, 1);
        ThreadPool pool(2);
        const FeatureMap expected = net.runReference(in, pool);
        const float scale = largestValue(expected);
        ASSERT_GT(scale, 0.f);
        for (unet::KernelIsa isa : kernelsHere()) {
            const FeatureMap out = net.run(in, pool, isa);
            ASSERT_EQ(out.values.size(), expected.values.size());
            float worst = 0;
            for (size_t i = 0; i < out.values.size(); ++i)
                worst = std::max(worst, std::fabs(out.values[i] - expected.values[i]));
            EXPECT_LT(worst / scale, 1e-5f) << unet::kernelIsaName(isa) << " with " << inputs;
        }
    }
}

TEST(UNetKernels, ResultsDoNotDependOnTheThreadsAndFusedMultiplyAddSetsAgree) {
    Rng rng(5);
    const UNet net = randomNet(rng, 9);
    const FeatureMap in = randomMap(9, 64, 48, rng, 0, 1);
    for (unet::KernelIsa isa : kernelsHere()) {
        ThreadPool one(1);
        const FeatureMap first = net.run(in, one, isa);
        for (int threads : {2, 3, 5}) {
            ThreadPool pool(threads);
            EXPECT_EQ(net.run(in, pool, isa).values, first.values)
                << unet::kernelIsaName(isa) << " on " << threads << " threads";
        }
    }
    // AVX2 and AVX-512 sum the same products in the same order, each fused: the same bits.
    if (unet::runs(unet::KernelIsa::Avx2) && unet::runs(unet::KernelIsa::Avx512)) {
        ThreadPool pool(2);
        EXPECT_EQ(net.run(in, pool, unet::KernelIsa::Avx2).values,
                  net.run(in, pool, unet::KernelIsa::Avx512).values);
    }
}

TEST(UNetKernels, KernelsAreNamedAndAnUnknownNameIsRefused) {
    for (unet::KernelIsa isa : kernelsHere())
        EXPECT_EQ(unet::kernelIsaNamed(unet::kernelIsaName(isa)), isa);
    EXPECT_TRUE(unet::runs(unet::bestKernelIsa()));
    EXPECT_THROW(unet::kernelIsaNamed("sse9"), std::invalid_argument);
}

}  // namespace
}  // namespace glint

namespace glint {
namespace {

struct NoisyImages {
    int width, height;
    std::vector<Vec3> color, albedo, normal;
    UNetImages images() const {
        return {width, height, color.data(), albedo.data(), normal.data()};
    }
};

NoisyImages noisyImages(int width, int height, Rng& rng) {
    NoisyImages n{width, height, {}, {}, {}};
    for (int i = 0; i < width * height; ++i) {
        n.color.emplace_back(std::exp(4 * rng.uniform() - 2), rng.uniform(), 3 * rng.uniform());
        n.albedo.emplace_back(rng.uniform(), rng.uniform(), rng.uniform());
        n.normal.emplace_back(2 * rng.uniform() - 1, 2 * rng.uniform() - 1, rng.uniform());
    }
    return n;
}

TEST(UNetFilter, TilesGiveTheWholeImagesResultBitForBit) {
    Rng rng(17);
    const UNet net = randomNet(rng, 9);
    // 330 x 40: padded to 336 x 48; tiles of 240 overlap by 112 and give 16 columns each.
    const NoisyImages in = noisyImages(330, 40, rng);
    ThreadPool pool(2);
    const std::vector<Vec3> whole = unetDenoise(net, in.images(), pool).pixels;
    ASSERT_EQ(unetTiles(net, 330, 40, {}).size(), 1u);
    UNetOptions tiled;
    tiled.tileSize = 240;
    EXPECT_EQ(unetTiles(net, 330, 40, tiled).size(), 21u);
    EXPECT_EQ(unetDenoise(net, in.images(), pool, tiled).pixels, whole);
    // Tiles from a memory limit (the least tile, 2 x 112 + 64 wide, giving 64 columns): the
    // same.
    UNetOptions small;
    small.maxMemoryBytes = 1;
    EXPECT_EQ(unetTiles(net, 330, 40, small).size(), 6u);
    EXPECT_EQ(unetDenoise(net, in.images(), pool, small).pixels, whole);
    // And the oracle agrees to rounding.
    UNetOptions reference;
    reference.isa = unet::KernelIsa::Reference;
    const std::vector<Vec3> expected = unetDenoise(net, in.images(), pool, reference).pixels;
    for (size_t i = 0; i < whole.size(); ++i)
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(whole[i][c], expected[i][c], 1e-3 * (1 + expected[i][c]));
    tiled.tileSize = 200;  // not more than twice the overlap
    EXPECT_THROW(unetDenoise(net, in.images(), pool, tiled), std::invalid_argument);
}

TEST(UNetFilter, ReceptiveRadiusCoversEveryLayerAndBytesGrowWithTheNetwork) {
    Rng rng(1);
    const UNet net = randomNet(rng, 9);
    // Base shape: 3 + (1 + 2*2) + (2 + 2*4) + (4 + 2*8) + (8 + 2*16) + (8 + 8) + (4 + 4) +
    // (2 + 2) + (1 + 2) = 109.
    EXPECT_EQ(net.receptiveRadius(), 109);
    EXPECT_GT(net.bytesPerPixel(), 4.0 * 16);  // the input's two blocks at least
}

}  // namespace
}  // namespace glint
