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

FeatureMap unetInput(const UNet& net, const UNetImages& in, float exposure) {
    const int channels = net.inputChannels();
    if (channels != 3 && channels != 6 && channels != 9)
        throw std::runtime_error("the network reads " + std::to_string(channels) +
                                 " channels: not colour, albedo and normal");
    if ((channels >= 6 && !in.albedo) || (channels == 9 && !in.normal))
        throw std::invalid_argument("the network needs the albedo and normal passes");
    auto aligned = [](int n) {
        return (n + UNet::kAlignment - 1) / UNet::kAlignment * UNet::kAlignment;
    };
    FeatureMap x(channels, aligned(in.height), aligned(in.width));
    for (int y = 0; y < in.height; ++y)
        for (int px = 0; px < in.width; ++px) {
            const size_t i = static_cast<size_t>(y) * in.width + px;
            for (int c = 0; c < 3; ++c) {
                const float v = sanitize(toFloat(in.color[i][c]) * exposure, 0.f, kMaxFloat);
                x.at(c, y, px) = puForward(v);
                if (channels >= 6)
                    x.at(3 + c, y, px) = sanitize(toFloat(in.albedo[i][c]), 0.f, 1.f);
                if (channels == 9)
                    x.at(6 + c, y, px) =
                        sanitize(toFloat(in.normal[i][c]), -1.f, 1.f) * 0.5f + 0.5f;
            }
        }
    return x;
}

std::vector<Vec3> unetDenoise(const UNet& net, const UNetImages& in, ThreadPool& pool,
                              unet::KernelIsa isa) {
    if (in.width <= 0 || in.height <= 0 || !in.color)
        throw std::invalid_argument("unetDenoise: no image");
    const float exposure = autoexposure(in.color, in.width, in.height);
    const FeatureMap out = net.run(unetInput(net, in, exposure), pool, isa);
    std::vector<Vec3> result(static_cast<size_t>(in.width) * in.height);
    const float unexpose = exposure != 0.f ? 1.f / exposure : 0.f;
    for (int y = 0; y < in.height; ++y)
        for (int x = 0; x < in.width; ++x) {
            Vec3& r = result[static_cast<size_t>(y) * in.width + x];
            for (int c = 0; c < 3; ++c)
                r[c] = puInverse(sanitize(out.at(c, y, x), 0.f, kMaxFloat)) * unexpose;
        }
    return result;
}

}  // namespace glint
