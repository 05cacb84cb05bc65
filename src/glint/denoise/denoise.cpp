#include "glint/denoise/denoise.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <utility>

#include "glint/denoise/nl_means.h"
#include "glint/denoise/plane.h"
#include "glint/denoise/tuning.h"

namespace glint {
namespace denoise_detail {
namespace {

using Planes = std::array<Plane, 3>;

float finite(double v) {
    const float f = static_cast<float>(v);
    return std::isfinite(f) ? f : 0.0f;
}

Planes makePlanes(int width, int height, int pad) {
    return {Plane(width, height, pad), Plane(width, height, pad), Plane(width, height, pad)};
}

/// A buffer of width x height colours as three planes (no border), non-finite values as 0.
Planes planesOf(const Vec3* v, int width, int height) {
    Planes p = makePlanes(width, height, 0);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            for (int c = 0; c < 3; ++c)
                p[c].at(x, y) = finite(v[static_cast<size_t>(y) * width + x][c]);
    return p;
}

std::array<const Plane*, 3> pointers(const Planes& p) { return {&p[0], &p[1], &p[2]}; }
std::array<Plane*, 3> pointers(Planes& p) { return {&p[0], &p[1], &p[2]}; }

/// The mean over a (2 radius + 1)^2 box, the image's edge pixels repeated beyond it. Writes
/// into `out` (same size); `in` needs a replicated border of at least `radius`.
void boxFilter(const Plane& in, int radius, Plane& out, ThreadPool& pool) {
    const int width = in.width(), height = in.height();
    const float norm = 1.0f / static_cast<float>((2 * radius + 1) * (2 * radius + 1));
    parallelFor(pool, 0, static_cast<size_t>(height), 16, [&](size_t first, size_t last) {
        std::vector<float> column(static_cast<size_t>(width) + 2 * radius);
        for (int y = static_cast<int>(first); y < static_cast<int>(last); ++y) {
            float* c = column.data() + radius;
            for (int x = -radius; x < width + radius; ++x) c[x] = 0;
            for (int j = -radius; j <= radius; ++j) {
                const float* r = in.row(y + j);
                for (int x = -radius; x < width + radius; ++x) c[x] += r[x];
            }
            float* o = out.row(y);
            for (int x = 0; x < width; ++x) {
                float s = 0;
                for (int i = -radius; i <= radius; ++i) s += c[x + i];
                o[x] = s * norm;
            }
        }
    });
}

/// The smaller in magnitude of two one-sided differences, 0 if they differ in sign: a surface's
/// slope that ignores a step to another surface beside it.
float minmod(float a, float b) {
    if (a * b <= 0) return 0.0f;
    return std::abs(a) < std::abs(b) ? a : b;
}

}  // namespace

std::vector<Vec3> denoiseTuned(const DenoiseInput& in, const DenoiseOptions& options,
                               const DenoiseTuning& tuning) {
    if (in.width < 0 || in.height < 0) throw std::invalid_argument("denoise: negative image size");
    const int width = in.width, height = in.height;
    const size_t count = static_cast<size_t>(width) * height;
    if (count == 0) return {};
    if (!in.color) throw std::invalid_argument("denoise: no colour buffer");

    std::optional<ThreadPool> ownPool;
    if (!options.pool) ownPool.emplace(options.threads);
    ThreadPool& pool = options.pool ? *options.pool : *ownPool;

    const bool twoPasses = tuning.second.radius > 0;
    const bool filterAlbedo = in.albedo && in.albedoVariance && tuning.albedo.radius > 0;
    const int pad = std::max({tuning.first.patch, twoPasses ? tuning.second.patch : 0,
                              filterAlbedo ? tuning.albedo.patch : 0, tuning.varianceRadius, 1});

    // Features.
    NlMeansGuide guide;
    Planes normal, albedo;
    Plane depth, depthDx, depthDy;
    if (in.normal) {
        normal = planesOf(in.normal, width, height);
        guide.normal = pointers(std::as_const(normal));
    }
    if (in.depth) {
        depth = Plane(width, height, 1);
        depthDx = Plane(width, height, 0);
        depthDy = Plane(width, height, 0);
        for (size_t i = 0; i < count; ++i)
            depth.at(static_cast<int>(i % width), static_cast<int>(i / width)) =
                std::max(finite(in.depth[i]), 0.0f);
        depth.replicateBorder();
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x) {
                const float d = depth.at(x, y);
                depthDx.at(x, y) = minmod(depth.at(x + 1, y) - d, d - depth.at(x - 1, y));
                depthDy.at(x, y) = minmod(depth.at(x, y + 1) - d, d - depth.at(x, y - 1));
            }
        guide.depth = &depth;
        guide.depthDx = &depthDx;
        guide.depthDy = &depthDy;
    }
    // The albedo, filtered where it is noisy (tuning.albedo): by itself and its variance, with
    // the normal and depth; `ownAlbedo` keeps the pixels' own for the demodulation.
    Planes ownAlbedo;
    if (in.albedo) {
        albedo = planesOf(in.albedo, width, height);
        if (filterAlbedo) {
            // The pixels' own albedo (kept for the demodulation) and its variance, with borders
            // for the patches; the filtered albedo goes to `albedo`.
            ownAlbedo = makePlanes(width, height, pad);
            Planes noise = makePlanes(width, height, pad);
            for (int y = 0; y < height; ++y)
                for (int x = 0; x < width; ++x)
                    for (int c = 0; c < 3; ++c) {
                        const size_t i = static_cast<size_t>(y) * width + x;
                        ownAlbedo[c].at(x, y) = albedo[c].at(x, y);
                        noise[c].at(x, y) = std::max(finite(in.albedoVariance[i][c]), 0.0f);
                    }
            for (int c = 0; c < 3; ++c) {
                ownAlbedo[c].replicateBorder();
                noise[c].replicateBorder();
            }
            NlMeansGuide g = guide;
            g.color = pointers(std::as_const(ownAlbedo));
            g.variance = pointers(std::as_const(noise));
            nlMeans(g, pointers(std::as_const(ownAlbedo)), tuning.albedo,
                    NlMeansOutputs{.value = pointers(albedo)}, nullptr, pool);
        }
        guide.albedo = pointers(std::as_const(albedo));
    }

    // Demodulation: colour divided by albedo where the albedo is large enough; `modulation`
    // keeps the divisor (1 where none) to multiply the result by at the end.
    Planes irradiance = makePlanes(width, height, pad);
    Planes modulation = makePlanes(width, height, 0);
    Planes variance = makePlanes(width, height, pad);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const size_t i = static_cast<size_t>(y) * width + x;
            for (int c = 0; c < 3; ++c) {
                // Divided by the albedo, but never by less than the floor: continuous in the
                // albedo (a cut-off that divides 0.011 by itself and 0.009 by 1 puts neighbours
                // 100 times apart, and the filter then carries the large ones over).
                float m = 1.0f, own = 1.0f;
                if (in.albedo) {
                    m = std::max(albedo[c].at(x, y), tuning.albedoFloor);
                    own = ownAlbedo[c].width() == 0
                              ? m
                              : std::max(ownAlbedo[c].at(x, y), tuning.albedoFloor);
                }
                modulation[c].at(x, y) = m;
                irradiance[c].at(x, y) = finite(in.color[i][c]) / own;
                if (in.variance)
                    variance[c].at(x, y) = std::max(finite(in.variance[i][c]), 0.0f) / (own * own);
            }
        }
    for (Plane& p : irradiance) p.replicateBorder();

    // Without a variance buffer, estimate it from each pixel's difference to the mean of its
    // two neighbours along each of four directions (row, column, diagonals): for independent
    // noise of variance v each has variance 3/2 v. The smallest of the four squares ignores
    // edges and texture along the other directions; the mean of the smallest of four squared
    // standard normal variables is 0.1208 (they are not quite independent: an estimate).
    if (!in.variance)
        for (int c = 0; c < 3; ++c)
            for (int y = 0; y < height; ++y)
                for (int x = 0; x < width; ++x) {
                    const Plane& u = irradiance[c];
                    const float p = u.at(x, y);
                    float m = 1e30f;
                    for (auto [i, j] : {std::pair{1, 0}, {0, 1}, {1, 1}, {1, -1}}) {
                        const float r = p - 0.5f * (u.at(x - i, y - j) + u.at(x + i, y + j));
                        m = std::min(m, r * r);
                    }
                    variance[c].at(x, y) = m * (tuning.estimatedVarianceScale / (1.5f * 0.1208f));
                }
    // The variance is as noisy as the colour: smooth it. `outliers` keeps the outliers' own
    // variance (0 elsewhere) for the second pass.
    Planes outliers = makePlanes(width, height, 0);
    {
        Planes smooth = makePlanes(width, height, pad);
        for (int c = 0; c < 3; ++c) {
            variance[c].replicateBorder();
            boxFilter(variance[c], tuning.varianceRadius, smooth[c], pool);
            if (tuning.outlierVariance > 0)
                for (int y = 0; y < height; ++y)
                    for (int x = 0; x < width; ++x) {
                        const float raw = variance[c].at(x, y);
                        if (raw > tuning.outlierVariance * smooth[c].at(x, y)) {
                            smooth[c].at(x, y) = raw;
                            outliers[c].at(x, y) = raw;
                        }
                    }
            smooth[c].replicateBorder();
        }
        variance = std::move(smooth);
    }

    // One pass of the filter over the noisy irradiance, weighted as `guide` says, into `out`
    // (and the variance of each result into `outVariance`, if given).
    const auto values = pointers(std::as_const(irradiance));
    const auto valueVariance = pointers(std::as_const(variance));
    auto pass = [&](const NlMeansParams& params, Planes& out, Planes* outVariance) {
        NlMeansOutputs o{.value = pointers(out)};
        if (outVariance) o.variance = pointers(*outVariance);
        nlMeans(guide, values, params, o, &valueVariance, pool);
    };

    // First pass: guided by the noisy irradiance.
    Planes first = makePlanes(width, height, pad);
    Planes firstVariance = makePlanes(width, height, pad);
    guide.color = pointers(std::as_const(irradiance));
    guide.variance = pointers(std::as_const(variance));
    pass(tuning.first, first, twoPasses ? &firstVariance : nullptr);
    const Planes* result = &first;

    // Second pass: the weights from the first pass's far less noisy result, the values again
    // the noisy irradiance.
    Planes second;
    if (twoPasses) {
        second = makePlanes(width, height, 0);
        for (int c = 0; c < 3; ++c) {
            first[c].replicateBorder();
            // An outlier's guide variance stays near its own, so that its neighbours take it in
            // as in the first pass rather than leave its energy out.
            for (int y = 0; y < height; ++y)
                for (int x = 0; x < width; ++x) {
                    float& v = firstVariance[c].at(x, y);
                    v = std::max(v * tuning.secondGuideVarianceScale,
                                 tuning.secondOutlierVariance * outliers[c].at(x, y));
                }
            firstVariance[c].replicateBorder();
        }
        guide.color = pointers(std::as_const(first));
        guide.variance = pointers(std::as_const(firstVariance));
        pass(tuning.second, second, nullptr);
        result = &second;
    }

    std::vector<Vec3> out(count);
    for (size_t i = 0; i < count; ++i) {
        const int x = static_cast<int>(i % width), y = static_cast<int>(i / width);
        for (int c = 0; c < 3; ++c) out[i][c] = (*result)[c].at(x, y) * modulation[c].at(x, y);
    }
    return out;
}

}  // namespace denoise_detail

std::vector<Vec3> denoise(const DenoiseInput& in, const DenoiseOptions& options) {
    return denoise_detail::denoiseTuned(in, options, {});
}

}  // namespace glint
