#pragma once
/// The measures a denoised image is judged by (its tests, bench/denoise_eval): images as pixel
/// vectors of the same size, row by row.

#include <vector>

#include "glint/math/vec3.h"

namespace glint {

/// Relative mean squared error against `ref`: the mean over pixels and channels of
/// (x - ref)^2 / (ref^2 + 0.01), as denoising papers (NFOR, OIDN's evaluations) report it.
inline double relMse(const std::vector<Vec3>& x, const std::vector<Vec3>& ref) {
    double sum = 0;
    for (size_t i = 0; i < x.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            const double e = x[i][c] - ref[i][c];
            sum += e * e / (ref[i][c] * ref[i][c] + 0.01);
        }
    return sum / (3.0 * static_cast<double>(x.size()));
}

/// The mean of every channel of every pixel.
inline double meanValue(const std::vector<Vec3>& x) {
    double s = 0;
    for (const Vec3& v : x) s += v.x + v.y + v.z;
    return s / (3.0 * static_cast<double>(x.size()));
}

}  // namespace glint
