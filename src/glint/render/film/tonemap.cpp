#include "glint/render/film/tonemap.h"

#include <algorithm>
#include <cmath>

namespace glint {
namespace {

/// Radiance as the tone mapper reads it: NaN and negative values 0, values above 1e30 (the
/// infinite ones among them) 1e30, where the compression is exactly 1 in double.
double clean(double v) {
    if (!(v > 0)) return 0;
    return std::min(v, 1e30);
}

}  // namespace

Vec3 pbrNeutral(const Vec3& input) {
    constexpr double kStart = kPbrNeutralStartCompression;
    constexpr double kDesaturation = 0.15;
    Vec3 c(clean(input.x), clean(input.y), clean(input.z));

    // 1. The black level: the smallest channel's offset, taken from every channel.
    const double x = std::min({c.x, c.y, c.z});
    const double offset = x < 0.08 ? x - 6.25 * x * x : 0.04;
    c = c - Vec3(offset);

    // 2. Below the start of compression: nothing more.
    const double peak = std::max({c.x, c.y, c.z});
    if (peak < kStart) return c;

    // 3. The peak compressed towards 1, every channel scaled alike.
    constexpr double d = 1 - kStart;
    const double newPeak = 1 - d * d / (peak + d - kStart);
    c = c * (newPeak / peak);

    // 4. Towards the grey of the new peak, by how much was compressed.
    const double g = 1 - 1 / (kDesaturation * (peak - newPeak) + 1);
    return c * (1 - g) + Vec3(newPeak * g);
}

Vec3 acesFilmic(const Vec3& input) {
    // Rows act on (r, g, b) columns: out_i = sum_j m[i][j] c_j.
    constexpr double kInput[3][3] = {
        {0.59719, 0.35458, 0.04823}, {0.07600, 0.90834, 0.01566}, {0.02840, 0.13383, 0.83777}};
    constexpr double kOutput[3][3] = {{1.60475, -0.53108, -0.07367},
                                      {-0.10208, 1.10813, -0.00605},
                                      {-0.00327, -0.07276, 1.07602}};
    constexpr double kExposureBoost = 1 / 0.6;
    const double c[3] = {clean(input.x) * kExposureBoost, clean(input.y) * kExposureBoost,
                         clean(input.z) * kExposureBoost};
    double fitted[3];
    for (int i = 0; i < 3; ++i) {
        const double v = kInput[i][0] * c[0] + kInput[i][1] * c[1] + kInput[i][2] * c[2];
        fitted[i] =
            (v * (v + 0.0245786) - 0.000090537) / (v * (0.983729 * v + 0.4329510) + 0.238081);
    }
    double out[3];
    for (int i = 0; i < 3; ++i) {
        const double v =
            kOutput[i][0] * fitted[0] + kOutput[i][1] * fitted[1] + kOutput[i][2] * fitted[2];
        out[i] = std::clamp(v, 0.0, 1.0);
    }
    return {out[0], out[1], out[2]};
}

Vec3 toneMap(ToneMap t, const Vec3& c) {
    if (t == ToneMap::PbrNeutral) return pbrNeutral(c);
    if (t == ToneMap::Aces) return acesFilmic(c);
    auto clamp01 = [](double v) { return v > 0 ? std::min(v, 1.0) : 0.0; };
    return {clamp01(c.x), clamp01(c.y), clamp01(c.z)};
}

}  // namespace glint
