#include "glint/render/film/display.h"

#include <algorithm>

#include "glint/render/film/tonemap.h"

namespace glint {

double srgbEncode(double linear) {
    if (!(linear > 0)) return 0;  // also NaN
    if (linear >= 1) return 1;
    if (linear <= 0.0031308) return 12.92 * linear;
    return 1.055 * std::pow(linear, 1 / 2.4) - 0.055;
}

uint8_t toByteSrgb(double linear) {
    // srgbEncode is within [0, 1], so the sum is within [0.5, 255.5]: no overflow.
    return static_cast<uint8_t>(std::min(255.0, 255 * srgbEncode(linear) + 0.5));
}

Image8 toImage8(const Film& film, const DisplayTransform& display) {
    if (display.isIdentity()) return toImage8(film);
    const double scale = display.scale();
    auto byte = display.srgb ? toByteSrgb : toByte;
    if (display.toneMap == ToneMap::Clamp)  // both byte conversions clamp
        return toImage8With(film, [&](double c) { return byte(scale * c); });
    // PBR Neutral maps whole pixels, not channels one by one.
    Image8 img{film.width(), film.height(), 3, {}};
    img.data.resize(static_cast<size_t>(img.width) * img.height * 3);
    size_t i = 0;
    for (int y = 0; y < film.height(); ++y)
        for (int x = 0; x < film.width(); ++x) {
            const Vec3 c = toneMap(display.toneMap, film.at(x, y) * scale);
            img.data[i++] = byte(c.x);
            img.data[i++] = byte(c.y);
            img.data[i++] = byte(c.z);
        }
    return img;
}

}  // namespace glint
