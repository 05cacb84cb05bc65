#pragma once
/// How a scene's linear radiance is meant to become 8-bit pixels (the conversion itself is in
/// render/film/display.h and render/film/tonemap.h). A scene carries its default; the command line
/// may override it (`--tonemap`, `--srgb`, `--no-srgb`).

#include <optional>
#include <string_view>

namespace glint {

/// What compresses radiance into [0, 1] before it is encoded.
enum class ToneMap {
    Clamp,       ///< Each channel clamped to [0, 1]: the course's conversion.
    PbrNeutral,  ///< Khronos PBR Neutral (render/film/tonemap.h): the glTF viewers' convention.
    Aces  ///< three.js's ACES filmic fit (render/film/tonemap.h): Khronos' Render Fidelity images.
};

struct DisplaySpec {
    ToneMap toneMap = ToneMap::Clamp;
    /// 8-bit outputs through the sRGB curve, rounded; false: the course's floor(255 c).
    bool srgb = false;
    /// Exposure in EV (radiance times 2^exposure) the scene is meant to be shown at: 0 but for
    /// a model lit by its own lights in physical units (model_framing.h); `--exposure`
    /// overrides it.
    double exposure = 0;

    bool operator==(const DisplaySpec&) const = default;
};

/// "clamp", "neutral" or "aces": the names `--tonemap` takes.
inline std::string_view toneMapName(ToneMap t) {
    switch (t) {
        case ToneMap::Clamp:
            return "clamp";
        case ToneMap::Aces:
            return "aces";
        default:
            return "neutral";
    }
}

/// The tone mapper called `name` ("clamp", "neutral", "aces"), if there is one.
inline std::optional<ToneMap> toneMapNamed(std::string_view name) {
    if (name == "clamp") return ToneMap::Clamp;
    if (name == "neutral") return ToneMap::PbrNeutral;
    if (name == "aces") return ToneMap::Aces;
    return std::nullopt;
}

}  // namespace glint
