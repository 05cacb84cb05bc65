#include "glint/denoise/unet/unet.h"

#include <algorithm>
#include <chrono>
#include <stdexcept>

namespace glint {
namespace {

/// The layer `name` of the archive, checked to take `in` channels (0: any).
Conv3x3 layer(const TzaTensors& tensors, const std::string& name, int in) {
    const auto w = tensors.find(name + ".weight"), b = tensors.find(name + ".bias");
    if (w == tensors.end() || b == tensors.end())
        throw std::runtime_error("the weights have no layer '" + name + "'");
    const TzaTensor& weights = w->second;
    if (weights.dims.size() != 4 || weights.dims[2] != 3 || weights.dims[3] != 3 ||
        weights.layout != "oihw")
        throw std::runtime_error("layer '" + name + "' is not a 3x3 convolution (oihw)");
    Conv3x3 conv{name, weights.dims[1], weights.dims[0], weights.values, b->second.values};
    if (static_cast<int>(conv.bias.size()) != conv.out)
        throw std::runtime_error("layer '" + name + "' has " + std::to_string(conv.bias.size()) +
                                 " biases for " + std::to_string(conv.out) + " outputs");
    if (in != 0 && conv.in != in)
        throw std::runtime_error("layer '" + name + "' takes " + std::to_string(conv.in) +
                                 " channels where the network gives it " + std::to_string(in));
    return conv;
}

bool has(const TzaTensors& tensors, const std::string& name) {
    return tensors.count(name + ".weight") != 0;
}

}  // namespace

UNet UNet::fromTensors(const TzaTensors& tensors) {
    UNet net;
    const bool large = has(tensors, "enc_conv1a");
    // The encoder, level by level: its layers chained, each taking the last one's output.
    int channels = 0;
    std::array<int, 4> skip{};  // the channels of each level's pooled output
    auto chain = [&](std::vector<Conv3x3>& out, std::initializer_list<std::string> names) {
        for (const std::string& name : names) {
            out.push_back(layer(tensors, name, channels));
            channels = out.back().out;
        }
    };
    for (int level = 1; level <= 4; ++level) {
        const std::string n = std::to_string(level);
        if (large)
            chain(net.encoder_[level - 1], {"enc_conv" + n + "a", "enc_conv" + n + "b"});
        else if (level == 1)
            chain(net.encoder_[0], {"enc_conv0", "enc_conv1"});
        else
            chain(net.encoder_[level - 1], {"enc_conv" + n});
        skip[level - 1] = channels;
    }
    chain(net.bottom_, {"enc_conv5a", "enc_conv5b"});
    const int input = net.encoder_[0].front().in;
    for (int level = 4; level >= 1; --level) {
        const std::string n = std::to_string(level);
        channels += level == 1 ? input : skip[level - 2];  // joined with the skip
        if (level > 1)
            chain(net.decoder_[level - 1], {"dec_conv" + n + "a", "dec_conv" + n + "b"});
        else
            chain(net.decoder_[0],
                  {"dec_conv1a", "dec_conv1b", large ? "dec_conv1c" : "dec_conv0"});
    }
    // Packed: every layer reads the one before it, but the decoder's first, which reads the
    // upsampled layer before it and the skip.
    auto pack = [](const std::vector<Conv3x3>& convs, std::vector<unet::PackedConv>& out,
                   int joined) {
        for (const Conv3x3& c : convs) {
            const bool join = &c == &convs.front() && joined > 0;
            const int sources[2] = {join ? c.in - joined : c.in, joined};
            out.push_back(unet::packConv(c, std::span<const int>(sources, join ? 2 : 1)));
        }
    };
    for (int level = 0; level < 4; ++level) {
        pack(net.encoder_[level], net.packedEncoder_[level], 0);
        pack(net.decoder_[level], net.packedDecoder_[level], level == 0 ? input : skip[level - 1]);
    }
    pack(net.bottom_, net.packedBottom_, 0);
    return net;
}

size_t UNet::parameters() const {
    size_t n = 0;
    auto count = [&](const std::vector<Conv3x3>& convs) {
        for (const Conv3x3& c : convs) n += c.weights.size() + c.bias.size();
    };
    for (const auto& level : encoder_) count(level);
    count(bottom_);
    for (const auto& level : decoder_) count(level);
    return n;
}

double UNet::multiplyAddsPerPixel() const {
    double perPixel = 0;
    auto count = [&](const std::vector<Conv3x3>& convs, double scale) {
        for (const Conv3x3& c : convs) perPixel += 9.0 * c.in * c.out * scale;
    };
    // Level L (from 1) of the encoder runs at 1 / 4^(L-1) of the pixels; the decoder's level L
    // too, and the bottom at 1 / 4^4.
    for (int level = 0; level < 4; ++level) {
        count(encoder_[level], 1.0 / (1 << (2 * level)));
        count(decoder_[level], 1.0 / (1 << (2 * level)));
    }
    count(bottom_, 1.0 / 256);
    return perPixel;
}

int UNet::receptiveRadius() const {
    // In input pixels: a 3x3 layer at scale s (pixels s apart) reaches s further; pooling into
    // and upsampling from scale 2s at most s. Backwards from the output through the bottom,
    // the longest way (every other way is part of it).
    int r = 0;
    for (int level = 0; level < 4; ++level) {
        const int s = 1 << level;
        if (level > 0) r += s / 2;  // the upsampling into this level
        r += static_cast<int>(decoder_[level].size()) * s;
    }
    r += 8 + static_cast<int>(bottom_.size()) * 16;
    for (int level = 3; level >= 0; --level) {
        const int s = 1 << level;
        r += s + static_cast<int>(encoder_[level].size()) * s;
    }
    return r;
}

double UNet::bytesPerPixel() const {
    // Floats per input pixel of a map of `channels` (whole blocks) at `level` (halved that often).
    auto floats = [](int channels, int level) {
        return static_cast<double>((channels + unet::kBlock - 1) / unet::kBlock * unet::kBlock) /
               (1 << (2 * level));
    };
    // Held throughout: the input and each level's pooled map; besides them, at most one
    // layer's input and output (the decoder's first layers read a half-size map).
    double held = floats(inputChannels(), 0), layer = 0;
    auto chain = [&](const std::vector<Conv3x3>& convs, int level, double in) {
        for (const Conv3x3& c : convs) {
            const double out = floats(c.out, level);
            layer = std::max(layer, in + out);
            in = out;
        }
    };
    for (int level = 0; level < 4; ++level) {
        held += floats(encoder_[level].back().out, level + 1);
        chain(encoder_[level], level, 0);
        chain(decoder_[level], level, floats(decoder_[level].front().in, level + 1));
    }
    chain(bottom_, 4, 0);
    return sizeof(float) * (held + layer);
}

namespace {

void checkInput(const UNet& net, const FeatureMap& input) {
    if (input.channels != net.inputChannels() || input.height % UNet::kAlignment != 0 ||
        input.width % UNet::kAlignment != 0 || input.height <= 0 || input.width <= 0)
        throw std::invalid_argument("UNet::run: the input has " + std::to_string(input.channels) +
                                    " channels of " + std::to_string(input.width) + "x" +
                                    std::to_string(input.height));
}

/// `convs` in turn, the first reading `sources` (of size height x width), each after it the one
/// before, the last pooled if `poolLast`, into a map from `maps`. In bands of rows, each band a
/// task that runs every layer on the rows it needs (the band and, for each layer before the
/// last, a row more either way for each layer after it) into maps of its own, and the last
/// layer into the result: so only the result is a whole map (a sixth of the memory the layers'
/// whole maps would take) and the bands stay in the caches. The rows a band computes twice
/// (with its neighbours) cost a few percent.
unet::BlockedMap chain(const std::vector<unet::PackedConv>& convs,
                       std::span<const unet::ConvSource> sources, int height, int width,
                       bool poolLast, unet::MapPool& maps, ThreadPool& pool, unet::KernelIsa isa) {
    using unet::BlockedMap;
    const int layers = static_cast<int>(convs.size());
    BlockedMap out = maps.take(convs.back().outChannels, poolLast ? height / 2 : height,
                               poolLast ? width / 2 : width);
    // Bands of 8 to 64 rows (even: pooling takes two), about four per thread.
    const int band = std::clamp(height / (4 * pool.threads()), 8, 64) / 2 * 2;
    const int bands = (height + band - 1) / band;
    const int perTask = unet::taskBlocks(isa);
    parallelFor(pool, 0, static_cast<size_t>(bands), 1, [&](size_t first, size_t last) {
        unet::AlignedFloats scratch(
            poolLast ? static_cast<size_t>(2) * width * perTask * unet::kBlock : 0, false);
        for (size_t i = first; i < last; ++i) {
            const int y0 = static_cast<int>(i) * band, y1 = std::min(height, y0 + band);
            BlockedMap before;  // the layer before's rows, from beforeRow
            int beforeRow = 0;
            for (int j = 0; j < layers; ++j) {
                const unet::PackedConv& conv = convs[static_cast<size_t>(j)];
                const int margin = layers - 1 - j;
                const int r0 = std::max(0, y0 - margin), r1 = std::min(height, y1 + margin);
                const bool isLast = j == layers - 1;
                BlockedMap rows =
                    isLast ? BlockedMap() : maps.take(conv.outChannels, r1 - r0, width);
                const unet::ConvSource previous{&before, false, beforeRow};
                unet::ConvRows t;
                t.conv = &conv;
                t.sources = j == 0 ? sources : std::span(&previous, 1);
                t.height = height;
                t.width = width;
                t.y0 = r0;
                t.y1 = r1;
                t.pool = isLast && poolLast;
                t.out = isLast ? &out : &rows;
                t.outFirstRow = isLast ? 0 : r0;
                t.scratch = scratch.data();
                for (t.block = 0; t.block < conv.outBlocks; t.block += perTask) {
                    t.blocks = std::min(perTask, conv.outBlocks - t.block);
                    unet::convolveRows(isa, t);
                }
                if (j > 0) maps.give(std::move(before));
                before = std::move(rows);
                beforeRow = r0;
            }
        }
    });
    return out;
}

double multiplyAdds(const std::vector<unet::PackedConv>& convs, int height, int width) {
    double n = 0;
    for (const unet::PackedConv& c : convs)
        n += 9.0 * c.inChannels * c.outChannels * width * height;
    return n;
}

}  // namespace

unet::BlockedMap UNet::run(const unet::BlockedMap& input, unet::MapPool& maps, ThreadPool& pool,
                           unet::KernelIsa isa, std::vector<UNetLayerTime>* times) const {
    if (input.channels != inputChannels() || input.height % kAlignment != 0 ||
        input.width % kAlignment != 0 || input.height <= 0 || input.width <= 0)
        throw std::invalid_argument("UNet::run: the input has " + std::to_string(input.channels) +
                                    " channels of " + std::to_string(input.width) + "x" +
                                    std::to_string(input.height));
    if (isa == unet::KernelIsa::Reference || !unet::runs(isa))
        throw std::invalid_argument("UNet::run: this machine does not run the " +
                                    std::string(unet::kernelIsaName(isa)) + " kernels");
    using unet::BlockedMap, unet::ConvSource;
    // Each level's layers as one chain (chain() above), timed as one.
    auto layers = [&](const std::vector<unet::PackedConv>& convs,
                      std::span<const ConvSource> sources, int height, int width, bool poolLast) {
        const auto start = std::chrono::steady_clock::now();
        BlockedMap out = chain(convs, sources, height, width, poolLast, maps, pool, isa);
        if (times)
            times->push_back(
                {convs.front().name + (convs.size() > 1 ? ".." + convs.back().name : ""), width,
                 height,
                 std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(),
                 multiplyAdds(convs, height, width)});
        return out;
    };
    std::array<BlockedMap, 4> pooled;
    for (int level = 0; level < 4; ++level) {
        const BlockedMap& from = level == 0 ? input : pooled[level - 1];
        const ConvSource source{&from, false};
        pooled[level] =
            layers(packedEncoder_[level], std::span(&source, 1), from.height, from.width, true);
    }
    const ConvSource bottom{&pooled[3], false};
    BlockedMap current =
        layers(packedBottom_, std::span(&bottom, 1), pooled[3].height, pooled[3].width, false);
    maps.give(std::move(pooled[3]));
    for (int level = 3; level >= 0; --level) {
        const BlockedMap& skip = level == 0 ? input : pooled[level - 1];
        const ConvSource join[2] = {{&current, true}, {&skip, false}};
        BlockedMap next = layers(packedDecoder_[level], join, skip.height, skip.width, false);
        maps.give(std::move(current));
        if (level > 0) maps.give(std::move(pooled[level - 1]));
        current = std::move(next);
    }
    return current;
}

FeatureMap UNet::run(const FeatureMap& input, ThreadPool& pool, unet::KernelIsa isa,
                     std::vector<UNetLayerTime>* times) const {
    if (isa == unet::KernelIsa::Reference) return runReference(input, pool);
    checkInput(*this, input);
    unet::MapPool maps;
    unet::BlockedMap x(input.channels, input.height, input.width);
    for (int c = 0; c < input.channels; ++c)
        for (int y = 0; y < input.height; ++y)
            for (int px = 0; px < input.width; ++px)
                x.at(c / unet::kBlock, y, px)[c % unet::kBlock] = input.at(c, y, px);
    const unet::BlockedMap result = run(x, maps, pool, isa, times);
    FeatureMap out(outputChannels(), input.height, input.width);
    for (int c = 0; c < out.channels; ++c)
        for (int y = 0; y < out.height; ++y)
            for (int px = 0; px < out.width; ++px)
                out.at(c, y, px) = result.at(c / unet::kBlock, y, px)[c % unet::kBlock];
    return out;
}

FeatureMap UNet::runReference(const FeatureMap& input, ThreadPool& pool) const {
    checkInput(*this, input);
    std::array<FeatureMap, 4> pooled;
    const FeatureMap* x = &input;
    FeatureMap current;
    for (int level = 0; level < 4; ++level) {
        for (const Conv3x3& conv : encoder_[level]) {
            current = convolveRelu(conv, *x, pool);
            x = &current;
        }
        pooled[level] = maxPool2x2(*x);
        x = &pooled[level];
    }
    for (const Conv3x3& conv : bottom_) {
        current = convolveRelu(conv, *x, pool);
        x = &current;
    }
    current = upsample2x(current);
    for (int level = 3; level >= 0; --level) {
        current = concatenate(current, level == 0 ? input : pooled[level - 1]);
        for (const Conv3x3& conv : decoder_[level]) current = convolveRelu(conv, current, pool);
        if (level > 0) current = upsample2x(current);
    }
    return current;
}

FeatureMap convolveRelu(const Conv3x3& conv, const FeatureMap& in, ThreadPool& pool) {
    const int h = in.height, w = in.width;
    FeatureMap out(conv.out, h, w);
    parallelFor(pool, 0, static_cast<size_t>(conv.out), 1, [&](size_t first, size_t last) {
        for (size_t o = first; o < last; ++o) {
            float* dst = out.plane(static_cast<int>(o));
            std::fill(dst, dst + static_cast<size_t>(h) * w, conv.bias[o]);
            for (int i = 0; i < conv.in; ++i) {
                const float* src = in.plane(i);
                const float* k = conv.weights.data() + (o * conv.in + i) * 9;
                for (int ky = 0; ky < 3; ++ky)
                    for (int kx = 0; kx < 3; ++kx) {
                        const float weight = k[ky * 3 + kx];
                        // out(y, x) += weight * in(y + ky - 1, x + kx - 1), zero outside.
                        const int y0 = std::max(0, 1 - ky), y1 = std::min(h, h + 1 - ky);
                        const int x0 = std::max(0, 1 - kx), x1 = std::min(w, w + 1 - kx);
                        for (int y = y0; y < y1; ++y) {
                            float* row = dst + static_cast<size_t>(y) * w;
                            const float* from =
                                src + static_cast<size_t>(y + ky - 1) * w + (kx - 1);
                            for (int xx = x0; xx < x1; ++xx) row[xx] += weight * from[xx];
                        }
                    }
            }
            for (size_t p = 0; p < static_cast<size_t>(h) * w; ++p) dst[p] = std::max(dst[p], 0.0f);
        }
    });
    return out;
}

FeatureMap maxPool2x2(const FeatureMap& in) {
    FeatureMap out(in.channels, in.height / 2, in.width / 2);
    for (int c = 0; c < in.channels; ++c)
        for (int y = 0; y < out.height; ++y)
            for (int x = 0; x < out.width; ++x)
                out.at(c, y, x) =
                    std::max(std::max(in.at(c, 2 * y, 2 * x), in.at(c, 2 * y, 2 * x + 1)),
                             std::max(in.at(c, 2 * y + 1, 2 * x), in.at(c, 2 * y + 1, 2 * x + 1)));
    return out;
}

FeatureMap upsample2x(const FeatureMap& in) {
    FeatureMap out(in.channels, in.height * 2, in.width * 2);
    for (int c = 0; c < in.channels; ++c)
        for (int y = 0; y < out.height; ++y)
            for (int x = 0; x < out.width; ++x) out.at(c, y, x) = in.at(c, y / 2, x / 2);
    return out;
}

FeatureMap concatenate(const FeatureMap& a, const FeatureMap& b) {
    if (a.height != b.height || a.width != b.width)
        throw std::invalid_argument("concatenate: images of different sizes");
    FeatureMap out(a.channels + b.channels, a.height, a.width);
    std::copy(a.values.begin(), a.values.end(), out.values.begin());
    std::copy(b.values.begin(), b.values.end(),
              out.values.begin() + static_cast<long>(a.values.size()));
    return out;
}

}  // namespace glint
