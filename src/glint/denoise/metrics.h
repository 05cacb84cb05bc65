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

/// How much of the reference's fine detail (texture, normal-map bumps, edges) an image keeps: the
/// slope of the image's high frequencies regressed on the reference's, sum(h_x h_ref) /
/// sum(h_ref^2), where h is a pixel's luminance, compressed as v / (1 + v), minus the mean of its
/// 3x3 neighbourhood. 1 keeps all of it, 0 none (a blur); noise uncorrelated with the reference
/// leaves the slope unbiased, so a raw render scores about 1 and a filter that smooths detail
/// away scores below. Images of `width` x `height` pixels, row by row.
inline double detailKept(const std::vector<Vec3>& x, const std::vector<Vec3>& ref, int width,
                         int height) {
    auto compressed = [&](const std::vector<Vec3>& image) {
        std::vector<double> l(image.size());
        for (size_t i = 0; i < image.size(); ++i) {
            const double v = std::max(0.0, luminance(image[i]));
            l[i] = v / (1 + v);
        }
        return l;
    };
    auto highPass = [&](const std::vector<double>& l, int px, int py) {
        double sum = 0;
        int n = 0;
        for (int v = std::max(0, py - 1); v <= std::min(height - 1, py + 1); ++v)
            for (int u = std::max(0, px - 1); u <= std::min(width - 1, px + 1); ++u, ++n)
                sum += l[static_cast<size_t>(v) * width + u];
        return l[static_cast<size_t>(py) * width + px] - sum / n;
    };
    const std::vector<double> lx = compressed(x), lr = compressed(ref);
    double cross = 0, energy = 0;
    for (int py = 0; py < height; ++py)
        for (int px = 0; px < width; ++px) {
            const double hr = highPass(lr, px, py);
            cross += highPass(lx, px, py) * hr;
            energy += hr * hr;
        }
    return energy > 0 ? cross / energy : 1;
}

/// The mean of every channel of every pixel.
inline double meanValue(const std::vector<Vec3>& x) {
    double s = 0;
    for (const Vec3& v : x) s += v.x + v.y + v.z;
    return s / (3.0 * static_cast<double>(x.size()));
}

}  // namespace glint
