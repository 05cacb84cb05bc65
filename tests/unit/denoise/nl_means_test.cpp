#include "glint/denoise/nl_means.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include "glint/core/parallel.h"
#include "glint/denoise/plane.h"

namespace glint::denoise_detail {
namespace {

// Three planes of a w x h image with a border of `pad`, each pixel set by `value(x, y, c)`.
template <typename F>
std::array<Plane, 3> planes(int w, int h, int pad, F value) {
    std::array<Plane, 3> p{Plane(w, h, pad), Plane(w, h, pad), Plane(w, h, pad)};
    for (int c = 0; c < 3; ++c) {
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) p[c].at(x, y) = value(x, y, c);
        p[c].replicateBorder();
    }
    return p;
}

std::array<const Plane*, 3> view(const std::array<Plane, 3>& p) { return {&p[0], &p[1], &p[2]}; }
std::array<Plane*, 3> view(std::array<Plane, 3>& p) { return {&p[0], &p[1], &p[2]}; }

// The guide is flat with a large variance, so that every weight is 1: the filter is then a
// plain mean (zero order) or a plain least-squares plane (first order) over the window.
struct FlatGuide {
    static constexpr int kW = 40, kH = 30;
    std::array<Plane, 3> color = planes(kW, kH, 1, [](int, int, int) { return 0.5f; });
    std::array<Plane, 3> variance = planes(kW, kH, 1, [](int, int, int) { return 1.0f; });
    NlMeansGuide guide() const {
        NlMeansGuide g;
        g.color = view(color);
        g.variance = view(variance);
        return g;
    }
};

TEST(NlMeans, AFirstOrderFitReproducesAPlaneUpToTheImageCorners) {
    const FlatGuide flat;
    // A steep plane, different per channel: a weighted mean flattens it where the window is
    // one-sided (the image's sides and corners); a fit of a plane reproduces it everywhere.
    auto truth = [](int x, int y, int c) {
        return 1.0f + 0.2f * static_cast<float>(x) - 0.1f * static_cast<float>((c + 1) * y);
    };
    const std::array<Plane, 3> values = planes(FlatGuide::kW, FlatGuide::kH, 1, truth);
    ThreadPool pool(2);
    for (bool firstOrder : {false, true}) {
        std::array<Plane, 3> out =
            planes(FlatGuide::kW, FlatGuide::kH, 0, [](int, int, int) { return 0.0f; });
        NlMeansParams params{.radius = 4, .patch = 1, .firstOrder = firstOrder, .ridge = 1e-6f};
        nlMeans(flat.guide(), view(values), params, {.value = view(out)}, nullptr, pool);
        float worst = 0;
        for (int c = 0; c < 3; ++c)
            for (int y = 0; y < FlatGuide::kH; ++y)
                for (int x = 0; x < FlatGuide::kW; ++x)
                    worst = std::max(worst, std::abs(out[c].at(x, y) - truth(x, y, c)));
        if (firstOrder)
            EXPECT_LT(worst, 1e-3f);
        else
            EXPECT_GT(worst, 0.5f);  // the corner: the mean of a 5x5 quarter window, 2 pixels off
    }
}

TEST(NlMeans, AFitsVarianceGrowsWhereItExtrapolates) {
    const FlatGuide flat;
    const std::array<Plane, 3> values =
        planes(FlatGuide::kW, FlatGuide::kH, 1,
               [](int x, int y, int) { return 0.01f * static_cast<float>(x * y); });
    const std::array<Plane, 3> unit =
        planes(FlatGuide::kW, FlatGuide::kH, 1, [](int, int, int) { return 1.0f; });
    const auto valueVariance = view(unit);
    ThreadPool pool(2);
    for (bool firstOrder : {false, true}) {
        std::array<Plane, 3> out =
            planes(FlatGuide::kW, FlatGuide::kH, 0, [](int, int, int) { return 0.0f; });
        std::array<Plane, 3> variance = out;
        NlMeansParams params{.radius = 4, .patch = 1, .firstOrder = firstOrder, .ridge = 1e-6f};
        nlMeans(flat.guide(), view(values), params,
                {.value = view(out), .variance = view(variance)}, &valueVariance, pool);
        // Inside, all 81 weights are 1: the mean's variance is 1/81, and so is the plane's (the
        // offsets' mean is 0: its constant is the mean).
        EXPECT_NEAR(variance[0].at(20, 15), 1.0f / 81, 1e-6f);
        // In the corner the window holds 25 pixels: the mean's variance is 1/25; the plane
        // extrapolates to the window's corner, its constant far noisier: for an unregularised
        // fit 1/25 (1 + 2^2 / 2 + 2^2 / 2) = 1/5 (the offsets' mean 2, their variance 2).
        if (firstOrder)
            EXPECT_NEAR(variance[0].at(0, 0), 0.2f, 1e-4f);
        else
            EXPECT_NEAR(variance[0].at(0, 0), 1.0f / 25, 1e-6f);
    }
}

}  // namespace
}  // namespace glint::denoise_detail
