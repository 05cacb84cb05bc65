#pragma once
/// Which reconstruction filter the scene asks for (the sampling is in render/film/filter.h).

#include <string_view>

namespace glint {

struct FilterSpec {
    enum class Kind { Box, Gaussian };
    Kind kind = Kind::Box;
    /// Half-width in pixels: the box covers [-radius, radius]^2 (0.5: exactly the pixel). The
    /// Gaussian has sigma = radius / 3 and is truncated at the radius.
    double radius = 0.5;

    bool operator==(const FilterSpec&) const = default;
    /// Default radius for a kind: 0.5 for the box, 1.5 (sigma 0.5 pixels) for the Gaussian.
    static double defaultRadius(Kind kind) { return kind == Kind::Box ? 0.5 : 1.5; }
};

/// "box" or "gaussian".
inline std::string_view filterName(FilterSpec::Kind kind) {
    return kind == FilterSpec::Kind::Box ? "box" : "gaussian";
}

}  // namespace glint
