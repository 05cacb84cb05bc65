#pragma once
/// Sampling a discrete or piecewise-constant distribution in proportion to given weights: the
/// choice of a light by its power, and the rows and columns of an environment map.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace glint {

/// A piecewise-constant density on [0, 1) with one cell per weight (weights >= 0), sampled by
/// inverting its cumulative distribution. Used as a discrete distribution too: sampleDiscrete
/// picks cell i with probability weight_i / sum. If every weight is 0 (or the sum is not
/// finite), it falls back to uniform.
class Distribution1D {
  public:
    Distribution1D() = default;
    explicit Distribution1D(std::vector<double> weights) : weights_(std::move(weights)) {
        const size_t n = weights_.size();
        cdf_.assign(n + 1, 0.0);
        for (size_t i = 0; i < n; ++i) {
            double w = weights_[i] > 0 && std::isfinite(weights_[i]) ? weights_[i] : 0.0;
            weights_[i] = w;
            cdf_[i + 1] = cdf_[i] + w;
        }
        total_ = n ? cdf_[n] : 0;
        if (!(total_ > 0) || !std::isfinite(total_)) {
            for (size_t i = 0; i < n; ++i) {
                weights_[i] = 1;
                cdf_[i + 1] = static_cast<double>(i + 1);
            }
            total_ = static_cast<double>(n);
        }
        for (double& c : cdf_) c /= total_;
        if (n) cdf_[n] = 1;
    }

    size_t size() const { return weights_.size(); }
    bool empty() const { return weights_.empty(); }
    /// Sum of the (clamped) weights, or the count if all were 0.
    double total() const { return total_; }

    /// Probability of cell `i` in a discrete draw.
    double probability(size_t i) const { return weights_[i] / total_; }

    /// The cell that `u` in [0, 1) falls in, with its probability, and `u` rescaled to [0, 1)
    /// within the cell (so that one uniform number can drive a further choice).
    size_t sampleDiscrete(double u, double* probability = nullptr,
                          double* uRemapped = nullptr) const {
        size_t i = find(u);
        double p = weights_[i] / total_;
        if (probability) *probability = p;
        if (uRemapped) *uRemapped = std::min((u - cdf_[i]) / (cdf_[i + 1] - cdf_[i]), kOneMinus);
        return i;
    }

    /// A point of [0, 1) with the piecewise-constant density (cell i's density is
    /// n weight_i / sum), and that density; `cell` receives the cell.
    double sampleContinuous(double u, double* density, size_t* cell = nullptr) const {
        size_t i = find(u);
        if (cell) *cell = i;
        double width = cdf_[i + 1] - cdf_[i];
        if (density) *density = weights_[i] * static_cast<double>(size()) / total_;
        double du = width > 0 ? (u - cdf_[i]) / width : 0.5;
        return std::min((static_cast<double>(i) + du) / static_cast<double>(size()), kOneMinus);
    }

    /// The density of sampleContinuous at x in [0, 1).
    double density(double x) const {
        size_t i = std::min(static_cast<size_t>(std::max(x, 0.0) * static_cast<double>(size())),
                            size() - 1);
        return weights_[i] * static_cast<double>(size()) / total_;
    }

  private:
    static constexpr double kOneMinus = 0x1.fffffffffffffp-1;
    /// The cell i with cdf_[i] <= u < cdf_[i + 1] and a positive weight.
    size_t find(double u) const {
        auto it = std::upper_bound(cdf_.begin(), cdf_.end(), u);
        size_t i = static_cast<size_t>(std::max<std::ptrdiff_t>(it - cdf_.begin() - 1, 0));
        i = std::min(i, size() - 1);
        // Cells of zero weight have zero width; u == cdf_[i] may land on one: step forward.
        while (i + 1 < size() && !(weights_[i] > 0)) ++i;
        while (i > 0 && !(weights_[i] > 0)) --i;
        return i;
    }

    std::vector<double> weights_;
    std::vector<double> cdf_;
    double total_ = 0;
};

}  // namespace glint
