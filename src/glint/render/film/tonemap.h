#pragma once
/// Tone mappers: functions from linear radiance (Rec. 709 primaries, any value >= 0) to linear
/// display values in [0, 1], applied before the sRGB curve.
///
/// **Khronos PBR Neutral** (Khronos Group, 2024; github.com/KhronosGroup/ToneMapping,
/// "PBR_Neutral"), the tone mapper of the glTF sample viewer, model-viewer and Blender's
/// "Khronos PBR Neutral" view. It is built so that a glTF base colour lit by a white light of
/// unit radiance shows as that base colour, and bright colours keep their hue:
///
/// 1. **Black level.** Let x be the smallest channel. Every channel is lowered by
///    offset = x - 6.25 x^2 when x < 0.08, else by 0.04: the 4% a dielectric's Fresnel
///    reflection (F0 = 0.04) adds on top of its diffuse colour is taken away again. The offset
///    is continuous with a continuous slope at x = 0.08 and keeps black black.
/// 2. **Identity below the start of compression.** If the largest channel after the offset,
///    the peak p, is below s = 0.8 - 0.04 = 0.76, that is the result: a colour changes by its
///    offset only.
/// 3. **Compression.** Otherwise the colour is scaled so that its peak becomes
///    p' = 1 - (1 - s)^2 / (p + 1 - 2 s), which is p at p = s (with slope 1) and tends to 1 as
///    p grows: every channel keeps its ratio to the others, so the hue is kept.
/// 4. **Desaturation.** The scaled colour is mixed towards the grey (p', p', p') with weight
///    g = 1 - 1 / (0.15 (p - p') + 1): the more a colour was compressed, the closer to white,
///    as a bright light looks on film. The peak stays p'.
///
/// So every output channel lies in [0, 1), the HSV hue of the input is kept (steps 1, 3 and 4
/// each add the same amount to every channel or scale them all alike), and a colour made
/// brighter never maps darker.
///
/// **ACES filmic** as three.js's ACESFilmicToneMapping computes it (Stephen Hill's fit of the
/// ACES reference rendering and output transforms; the coefficients are the published ones, as
/// three.js, the glTF Sample Viewer and the Khronos glTF Render Fidelity scripts use them):
/// radiance times 1/0.6 (three.js's exposure boost), into the ACES working space by a 3x3
/// matrix, each channel through (c (c + 0.0245786) - 0.000090537) /
/// (c (0.983729 c + 0.4329510) + 0.238081), back by a second matrix, clamped to [0, 1]. The
/// Render Fidelity images of Cycles and V-Ray then encode with a plain 2.2 gamma where Glint
/// uses the sRGB curve: at most about 2 levels of 255 apart in the mid-tones.

#include "glint/math/vec3.h"
#include "glint/scene/display_spec.h"

namespace glint {

/// Khronos PBR Neutral of linear radiance `c`, as the file comment describes. Negative and
/// NaN channels are read as 0, infinite ones as very large: the result is always in [0, 1].
Vec3 pbrNeutral(const Vec3& c);

/// The largest channel at which PBR Neutral starts compressing (after the black-level offset).
inline constexpr double kPbrNeutralStartCompression = 0.8 - 0.04;

/// three.js's ACES filmic fit of linear radiance `c`, as the file comment describes; in [0, 1].
Vec3 acesFilmic(const Vec3& c);

/// `c` through the tone mapper `t`: Clamp clamps every channel to [0, 1] (NaN to 0).
Vec3 toneMap(ToneMap t, const Vec3& c);

}  // namespace glint
