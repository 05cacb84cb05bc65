#pragma once
/// Display transforms: what turns the film's linear radiance into the values an image file
/// stores. Exposure scales every output; the tone mapper and the sRGB curve are for 8-bit
/// outputs only.

#include <cmath>
#include <cstdint>

#include "glint/render/film/film.h"
#include "glint/scene/display_spec.h"

namespace glint {

/// How the film is turned into output values. The default (exposure 0, clamp, no sRGB) is the
/// course's plain conversion, bit for bit.
struct DisplayTransform {
    double exposure = 0;  ///< EV: radiance is multiplied by 2^exposure, for every format.
    bool srgb = false;    ///< 8-bit outputs only: encode with the sRGB curve, then round.
    /// 8-bit outputs only: what brings the exposed radiance into [0, 1] (render/film/tonemap.h).
    ToneMap toneMap = ToneMap::Clamp;

    /// The factor 2^exposure (exactly 1 for the default).
    double scale() const { return std::exp2(exposure); }
    bool isIdentity() const { return exposure == 0 && !srgb && toneMap == ToneMap::Clamp; }
};

/// The sRGB transfer function of IEC 61966-2-1 (linear to encoded), for c in [0, 1]:
/// 12.92 c up to 0.0031308, then 1.055 c^(1/2.4) - 0.055. Values outside [0, 1] are clamped
/// first; NaN gives 0.
double srgbEncode(double linear);

/// One 8-bit sRGB level: clamp, encode, then round to nearest, round(255 * srgbEncode(c)).
/// NaN becomes 0.
uint8_t toByteSrgb(double linear);

/// The 8-bit image of `film` under `display`: each channel multiplied by 2^exposure, the pixel
/// tone-mapped (clamped per channel, or PBR Neutral), then each channel either the course's
/// floor(255 c) (toByte) or, with srgb, rounded through the sRGB curve (toByteSrgb).
Image8 toImage8(const Film& film, const DisplayTransform& display);

}  // namespace glint
