#pragma once
/// The measures a denoised image is judged by (its tests, bench/denoise_eval): images as pixel
/// vectors of the same size, row by row.

#include <algorithm>
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

/// relMse() without the `fraction` of pixels whose error is largest (a handful of fireflies in
/// the reference or the image cannot decide it): bench/denoise/relmse.py's "relMSE-trim".
inline double relMseTrimmed(const std::vector<Vec3>& x, const std::vector<Vec3>& ref,
                            double fraction = 0.001) {
    std::vector<double> perPixel(x.size());
    for (size_t i = 0; i < x.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            const double e = x[i][c] - ref[i][c];
            perPixel[i] += e * e / (ref[i][c] * ref[i][c] + 0.01);
        }
    std::sort(perPixel.begin(), perPixel.end());
    const size_t kept = x.size() - static_cast<size_t>(static_cast<double>(x.size()) * fraction);
    double sum = 0;
    for (size_t i = 0; i < kept; ++i) sum += perPixel[i];
    return kept ? sum / (3.0 * static_cast<double>(kept)) : 0;
}

/// The mean of every channel of every pixel.
inline double meanValue(const std::vector<Vec3>& x) {
    double s = 0;
    for (const Vec3& v : x) s += v.x + v.y + v.z;
    return s / (3.0 * static_cast<double>(x.size()));
}

}  // namespace glint
