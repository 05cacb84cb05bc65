#include "glint/denoise/unet/unet_filter.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace glint {
namespace {

// The PU curve's fit, as OIDN publishes it (its transfer function's constants).
constexpr float kA = 1.41283765e+03f, kB = 1.64593172e+00f, kC = 4.31384981e-01f,
                kD = -2.94139609e-03f, kE = 1.92653254e-01f, kF = 6.26026094e-03f,
                kG = 9.98620152e-01f, kY0 = 1.57945760e-06f, kY1 = 3.22087631e-02f,
                kX0 = 2.23151711e-03f, kX1 = 3.70974749e-01f;
constexpr float kMaxHdr = 65504.f;  // the largest half: the transfer function's range
constexpr float kMaxFloat = std::numeric_limits<float>::max();  // OIDN's clamp

float puRaw(float y) {
    if (y <= kY0) return kA * y;
    if (y <= kY1) return kB * std::pow(y, kC) + kD;
    return kE * std::log(y + kF) + kG;
}

float puRawInverse(float x) {
    if (x <= kX0) return x / kA;
    if (x <= kX1) return std::pow((x - kD) / kB, 1.f / kC);
    return std::exp((x - kG) / kE) - kF;
}

const float kNormScale = 1.f / puRaw(kMaxHdr);

float sanitize(float v, float lo, float hi) {
    return std::isfinite(v) ? std::clamp(v, lo, hi) : 0.f;
}

/// A double as a float, infinite beyond float's range (converting such a double is undefined).
float toFloat(double v) {
    if (v > kMaxFloat) return std::numeric_limits<float>::infinity();
    if (v < -kMaxFloat) return -std::numeric_limits<float>::infinity();
    return static_cast<float>(v);
}

float luminance(const Vec3& c) {
    auto s = [](double v) { return sanitize(toFloat(v), 0.f, kMaxFloat); };
    return 0.212671f * s(c.x) + 0.715160f * s(c.y) + 0.072169f * s(c.z);
}

}  // namespace

float puForward(float radiance) { return puRaw(radiance) * kNormScale; }
float puInverse(float value) { return puRawInverse(value / kNormScale); }

float autoexposure(const Vec3* color, int width, int height) {
    constexpr int kMaxBin = 16;
    const int binsY = (height + kMaxBin - 1) / kMaxBin, binsX = (width + kMaxBin - 1) / kMaxBin;
    float logSum = 0;
    int count = 0;
    for (int i = 0; i < binsY; ++i)
        for (int j = 0; j < binsX; ++j) {
            const int y0 = static_cast<int>(static_cast<long long>(i) * height / binsY);
            const int y1 = static_cast<int>(static_cast<long long>(i + 1) * height / binsY);
            const int x0 = static_cast<int>(static_cast<long long>(j) * width / binsX);
            const int x1 = static_cast<int>(static_cast<long long>(j + 1) * width / binsX);
            float sum = 0;
            for (int y = y0; y < y1; ++y)
                for (int x = x0; x < x1; ++x)
                    sum += luminance(color[static_cast<size_t>(y) * width + x]);
            const float mean = sum / static_cast<float>((y1 - y0) * (x1 - x0));
            if (mean > 1e-8f) {
                logSum += std::log2(mean);
                ++count;
            }
        }
    return count > 0 ? 0.18f / std::exp2(logSum / static_cast<float>(count)) : 1.f;
}

namespace {

/// Input pixel i's channels for `net`, as unetInput() maps them, into `out` (9 floats: colour,
/// albedo, normal; those the network does not read zero).
void inputPixel(const UNetImages& in, size_t i, float exposure, int channels, float* out) {
    std::fill(out, out + 9, 0.f);
    for (int c = 0; c < 3; ++c) {
        const float v = toFloat(in.color[i][c]);
        switch (in.role) {
            case UNetRole::HdrColor:
                out[c] = puForward(sanitize(v * exposure, 0.f, kMaxFloat));
                if (channels >= 6) out[3 + c] = sanitize(toFloat(in.albedo[i][c]), 0.f, 1.f);
                if (channels == 9)
                    out[6 + c] = sanitize(toFloat(in.normal[i][c]), -1.f, 1.f) * 0.5f + 0.5f;
                break;
            case UNetRole::Albedo:
                out[c] = sanitize(v, 0.f, 1.f);
                break;
            case UNetRole::Normal:
                out[c] = sanitize(v, -1.f, 1.f) * 0.5f + 0.5f;
                break;
        }
    }
}

/// The network's output `value` (one channel) as the image's: clamped at 0 (OIDN's outputs may
/// be negative), then colour through the transfer function's inverse and the exposure, an
/// albedo clamped to 1, a normal mapped back to [-1, 1].
float outputValue(UNetRole role, float value, float unexpose) {
    value = sanitize(value, 0.f, kMaxFloat);
    switch (role) {
        case UNetRole::HdrColor:
            return puInverse(value) * unexpose;
        case UNetRole::Albedo:
            return std::min(value, 1.f);
        case UNetRole::Normal:
            return std::min(value * 2.f - 1.f, 1.f);
    }
    return value;
}

/// Pixels with a value that is not finite in an image the network reads.
size_t nonFinitePixels(const UNetImages& in, int channels) {
    const size_t n = static_cast<size_t>(in.width) * in.height;
    auto bad = [](const Vec3* image, size_t i) {
        return image && !(std::isfinite(image[i].x) && std::isfinite(image[i].y) &&
                          std::isfinite(image[i].z));
    };
    size_t count = 0;
    const bool aux = in.role == UNetRole::HdrColor;
    for (size_t i = 0; i < n; ++i)
        count += bad(in.color, i) || (aux && channels >= 6 && bad(in.albedo, i)) ||
                 (aux && channels == 9 && bad(in.normal, i));
    return count;
}

void checkImages(const UNet& net, const UNetImages& in) {
    if (in.width <= 0 || in.height <= 0 || !in.color)
        throw std::invalid_argument("unetDenoise: no image");
    const int channels = net.inputChannels();
    if (in.role != UNetRole::HdrColor ? channels != 3
                                      : channels != 3 && channels != 6 && channels != 9)
        throw std::runtime_error("the network reads " + std::to_string(channels) +
                                 " channels: not colour, albedo and normal");
    if (in.role == UNetRole::HdrColor &&
        ((channels >= 6 && !in.albedo) || (channels == 9 && !in.normal)))
        throw std::invalid_argument("the network needs the albedo and normal passes");
}

int roundUp(int n, int to) { return (n + to - 1) / to * to; }

/// The windows along one side of `extent` pixels (`padded` with the padding): (start, size)
/// and the pixels [first, last) whose output each gives.
struct Span {
    int start, size, first, last;
};
std::vector<Span> spans(int extent, int padded, int tile, int overlap) {
    if (padded <= tile) return {{0, padded, 0, extent}};
    // Each window gives the `step` pixels `overlap` from its edges; the last ones are moved in
    // to end at the image's edge, and still reach `overlap` past what they give (16 > padding).
    const int step = tile - 2 * overlap;
    std::vector<Span> out;
    for (int first = 0; first < extent; first += step)
        out.push_back({std::clamp(first - overlap, 0, padded - tile), tile, first,
                       std::min(first + step, extent)});
    return out;
}

/// The tiles' width and height for an image padded to `width` x `height`: the whole image if
/// it fits the memory, else the widest rows of tiles that do (square ones where neither side
/// fits), never less than the overlap needs.
std::array<int, 2> tileSize(const UNet& net, const UNetOptions& options, int overlap, int width,
                            int height) {
    const int least = 2 * overlap + 4 * UNet::kAlignment;
    if (options.tileSize > 0) {
        if (options.tileSize % UNet::kAlignment != 0 || options.tileSize <= 2 * overlap)
            throw std::invalid_argument(
                "unetDenoise: tiles of " + std::to_string(options.tileSize) +
                " pixels: not a multiple of 16 more than " + std::to_string(2 * overlap));
        return {options.tileSize, options.tileSize};
    }
    const double pixels = std::max(options.maxMemoryBytes / net.bytesPerPixel(), 0.0);
    const int side = std::max(static_cast<int>(std::sqrt(pixels)) / 16 * 16, least);
    const int tall = std::min(height, side);
    const int wide = std::max(static_cast<int>(pixels / tall) / 16 * 16, side);
    return {std::min(width, wide), tall};
}

/// The tiles of an image of width x height, as spans along x and y.
std::vector<std::pair<Span, Span>> tiling(const UNet& net, int width, int height,
                                          const UNetOptions& options) {
    const int overlap = roundUp(net.receptiveRadius(), UNet::kAlignment);
    const int paddedWidth = roundUp(width, UNet::kAlignment);
    const int paddedHeight = roundUp(height, UNet::kAlignment);
    const auto [w, h] = tileSize(net, options, overlap, paddedWidth, paddedHeight);
    std::vector<std::pair<Span, Span>> out;
    for (const Span& y : spans(height, paddedHeight, h, overlap))
        for (const Span& x : spans(width, paddedWidth, w, overlap)) out.emplace_back(x, y);
    return out;
}

}  // namespace

FeatureMap unetInput(const UNet& net, const UNetImages& in, float exposure) {
    checkImages(net, in);
    const int channels = net.inputChannels();
    FeatureMap x(channels, roundUp(in.height, UNet::kAlignment),
                 roundUp(in.width, UNet::kAlignment));
    float v[9];
    for (int y = 0; y < in.height; ++y)
        for (int px = 0; px < in.width; ++px) {
            inputPixel(in, static_cast<size_t>(y) * in.width + px, exposure, channels, v);
            for (int c = 0; c < channels; ++c) x.at(c, y, px) = v[c];
        }
    return x;
}

std::vector<std::array<int, 4>> unetTiles(const UNet& net, int width, int height,
                                          const UNetOptions& options) {
    std::vector<std::array<int, 4>> out;
    for (const auto& [x, y] : tiling(net, width, height, options))
        out.push_back({x.start, y.start, x.size, y.size});
    return out;
}

UNetResult unetDenoise(const UNet& net, const UNetImages& in, ThreadPool& pool,
                       const UNetOptions& options) {
    checkImages(net, in);
    const float exposure =
        in.role == UNetRole::HdrColor ? autoexposure(in.color, in.width, in.height) : 1.f;
    const float unexpose = exposure != 0.f ? 1.f / exposure : 0.f;
    UNetResult done;
    done.nonFinite = nonFinitePixels(in, net.inputChannels());
    std::vector<Vec3>& result = done.pixels;
    result.resize(static_cast<size_t>(in.width) * in.height);
    auto output = [&](float value) { return outputValue(in.role, value, unexpose); };
    if (options.isa == unet::KernelIsa::Reference) {
        const FeatureMap out = net.runReference(unetInput(net, in, exposure), pool);
        for (int y = 0; y < in.height; ++y)
            for (int x = 0; x < in.width; ++x)
                for (int c = 0; c < 3; ++c)
                    result[static_cast<size_t>(y) * in.width + x][c] = output(out.at(c, y, x));
        return done;
    }
    const int channels = net.inputChannels();
    unet::MapPool maps;  // every tile the same size: each takes the last one's maps
    for (const auto& tile : tiling(net, in.width, in.height, options)) {
        // (Not a structured binding: the web build's clang 14 cannot capture one in a lambda.)
        const Span &tx = tile.first, &ty = tile.second;
        unet::BlockedMap x = maps.take(channels, ty.size, tx.size);
        parallelFor(pool, 0, static_cast<size_t>(ty.size), 16, [&](size_t y0, size_t y1) {
            float v[2 * unet::kBlock] = {};
            for (int y = static_cast<int>(y0); y < static_cast<int>(y1); ++y)
                for (int px = 0; px < tx.size; ++px) {
                    const int iy = ty.start + y, ix = tx.start + px;
                    if (iy < in.height && ix < in.width)
                        inputPixel(in, static_cast<size_t>(iy) * in.width + ix, exposure, channels,
                                   v);
                    else
                        std::fill(v, v + 9, 0.f);
                    // Colour, albedo and normal in the blocks' first channels, zeros after.
                    for (int b = 0; b < x.blocks; ++b)
                        std::copy(v + b * unet::kBlock, v + (b + 1) * unet::kBlock, x.at(b, y, px));
                }
        });
        unet::BlockedMap out = net.run(x, maps, pool, options.isa, options.times);
        parallelFor(pool, static_cast<size_t>(ty.first), static_cast<size_t>(ty.last), 16,
                    [&](size_t y0, size_t y1) {
                        for (size_t y = y0; y < y1; ++y)
                            for (int ix = tx.first; ix < tx.last; ++ix) {
                                const float* o =
                                    out.at(0, static_cast<int>(y) - ty.start, ix - tx.start);
                                Vec3& r = result[y * in.width + ix];
                                for (int c = 0; c < 3; ++c) r[c] = output(o[c]);
                            }
                    });
        maps.give(std::move(x));
        maps.give(std::move(out));
    }
    return done;
}

}  // namespace glint
