#include "glint/scene/texture.h"

#include <algorithm>
#include <cmath>

namespace glint {
namespace {

/// The 256 decoded values of sRGB bytes, computed once.
const std::array<double, 256>& srgbTable() {
    static const std::array<double, 256> table = [] {
        std::array<double, 256> t{};
        for (int i = 0; i < 256; ++i) {
            double c = i / 255.0;
            t[static_cast<size_t>(i)] =
                c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
        }
        return t;
    }();
    return table;
}

/// A texel index for the integer position `i` (perhaps -1 or n) on an axis of `n` texels.
int wrapIndex(int i, int n, TextureWrap wrap) {
    if (wrap == TextureWrap::Clamp) return std::clamp(i, 0, n - 1);
    if (wrap == TextureWrap::MirroredRepeat) {  // period 2n: 0 .. n-1, then n-1 .. 0
        i %= 2 * n;
        if (i < 0) i += 2 * n;
        return i < n ? i : 2 * n - 1 - i;
    }
    i %= n;
    return i < 0 ? i + n : i;
}

/// `x` reduced to [0, 1] by the wrap mode, 0 if not finite.
double wrapCoordinate(double x, TextureWrap wrap) {
    if (!std::isfinite(x)) return 0;
    if (wrap == TextureWrap::Clamp) return std::clamp(x, 0.0, 1.0);
    if (wrap == TextureWrap::MirroredRepeat) {
        double f = x - 2 * std::floor(x / 2);  // [0, 2)
        f = f <= 1 ? f : 2 - f;
        return std::clamp(f, 0.0, 1.0);
    }
    double f = x - std::floor(x);
    return f < 1 ? f : 0;  // x just below an integer can round up to 1
}

}  // namespace

double srgbToLinear(uint8_t byte) { return srgbTable()[byte]; }

Vec3 TextureImage::texel(int x, int y) const {
    const uint8_t* p = rgb.data() + (static_cast<size_t>(y) * width + x) * 3;
    if (srgb) {
        const auto& t = srgbTable();
        return {t[p[0]], t[p[1]], t[p[2]]};
    }
    return Vec3(p[0], p[1], p[2]) * (1 / 255.0);
}

Vec3 TextureImage::average() const {
    Vec3 sum(0);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) sum += texel(x, y);
    size_t n = static_cast<size_t>(width) * height;
    return n ? sum * (1.0 / static_cast<double>(n)) : sum;
}

namespace {

/// The four texels around (u, v) and their bilinear weights.
struct Footprint {
    int xa, xb, ya, yb;
    double fx, fy;
};

Footprint footprint(const TextureImage& image, double u, double v, TextureWrap wrapS,
                    TextureWrap wrapT) {
    const int w = image.width, h = image.height;
    // Texel centres sit at (i + 0.5) / w; row 0 is the top, v = 1.
    double x = wrapCoordinate(u, wrapS) * w - 0.5;
    double y = (1 - wrapCoordinate(v, wrapT)) * h - 0.5;
    double x0 = std::floor(x), y0 = std::floor(y);
    // x and y lie in [-0.5, w - 0.5] and [-0.5, h - 0.5]: the casts are safe.
    int ix = static_cast<int>(x0), iy = static_cast<int>(y0);
    return {wrapIndex(ix, w, wrapS),
            wrapIndex(ix + 1, w, wrapS),
            wrapIndex(iy, h, wrapT),
            wrapIndex(iy + 1, h, wrapT),
            x - x0,
            y - y0};
}

}  // namespace

Vec3 sampleBilinear(const TextureImage& image, double u, double v, TextureWrap wrap) {
    const Footprint f = footprint(image, u, v, wrap, wrap);
    Vec3 top = image.texel(f.xa, f.ya) * (1 - f.fx) + image.texel(f.xb, f.ya) * f.fx;
    Vec3 bottom = image.texel(f.xa, f.yb) * (1 - f.fx) + image.texel(f.xb, f.yb) * f.fx;
    return top * (1 - f.fy) + bottom * f.fy;
}

Rgba sampleBilinearRgba(const TextureImage& image, double u, double v, TextureWrap wrapS,
                        TextureWrap wrapT) {
    const Footprint f = footprint(image, u, v, wrapS, wrapT);
    Vec3 top = image.texel(f.xa, f.ya) * (1 - f.fx) + image.texel(f.xb, f.ya) * f.fx;
    Vec3 bottom = image.texel(f.xa, f.yb) * (1 - f.fx) + image.texel(f.xb, f.yb) * f.fx;
    Rgba out{top * (1 - f.fy) + bottom * f.fy, 1};
    if (!image.alpha.empty()) {
        double at = image.alphaTexel(f.xa, f.ya) * (1 - f.fx) + image.alphaTexel(f.xb, f.ya) * f.fx;
        double ab = image.alphaTexel(f.xa, f.yb) * (1 - f.fx) + image.alphaTexel(f.xb, f.yb) * f.fx;
        out.a = at * (1 - f.fy) + ab * f.fy;
    }
    return out;
}

int checkerParity(double x, double scale) {
    double cell = std::floor(x / scale);
    if (!std::isfinite(cell)) return 0;
    return std::abs(std::fmod(cell, 2.0)) == 1.0 ? 1 : 0;
}

Vec3 Texture::eval(bool hasUv, double u, double v, const Vec3& p, const Vec3& fallback) const {
    if (kind == Kind::Image) {
        if (!hasUv || !image || image->width <= 0 || image->height <= 0) return fallback;
        return a * sampleBilinear(*image, u, v, wrap);
    }
    int parity;
    if (hasUv) {
        parity = checkerParity(u, scale) ^ checkerParity(v, scale);
    } else {
        // Cell boundaries at (k + 1/2) scale: surfaces at whole multiples of the scale, such as
        // a floor at y = 0, lie in the middle of a cell instead of flickering across a boundary.
        double half = 0.5 * scale;
        parity = checkerParity(p.x + half, scale) ^ checkerParity(p.y + half, scale) ^
                 checkerParity(p.z + half, scale);
    }
    return parity ? b : a;
}

}  // namespace glint
