#include "glint/render/tonemap.h"

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

Vec3 toneMap(ToneMap t, const Vec3& c) {
    if (t == ToneMap::PbrNeutral) return pbrNeutral(c);
    auto clamp01 = [](double v) { return v > 0 ? std::min(v, 1.0) : 0.0; };
    return {clamp01(c.x), clamp01(c.y), clamp01(c.z)};
}

}  // namespace glint
