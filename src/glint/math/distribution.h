#pragma once
/// Sampling a discrete or piecewise-constant distribution in proportion to given weights: the
/// choice of a light by its power (Distribution1D), and the texels of an environment map
/// (Distribution2D: its rows, then a column within the row).

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "glint/math/sampling.h"

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
        // The guide: for each of n buckets [k / n, (k + 1) / n) of u, where its search starts.
        guide_.resize(n ? n + 1 : 0);
        for (size_t k = 0; k < guide_.size(); ++k)
            guide_[k] = static_cast<uint32_t>(
                lastAtMost(static_cast<double>(k) / static_cast<double>(n), 0, cdf_.size()));
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
        // The last i with !(u < cdf_[i]), as std::upper_bound's result less one. The guide
        // narrows the search to a few cells around u's bucket (u's bucket k is within one of
        // floor(u n), whatever the rounding; cells at most guide_[k + 2] have cdf at most u):
        // the same cell as a search of the whole table, found in constant expected time.
        size_t i;
        const size_t n = size();
        if (u >= 0 && u < 1 && !guide_.empty()) {
            size_t k = std::min(static_cast<size_t>(u * static_cast<double>(n)), n - 1);
            size_t lo = guide_[k == 0 ? 0 : k - 1], hi = guide_[std::min(k + 2, n)];
            i = lastAtMost(u, lo, hi + 1);
        } else {
            i = lastAtMost(u, 0, cdf_.size());
        }
        i = std::min(i, n - 1);
        // Cells of zero weight have zero width; u == cdf_[i] may land on one: step forward.
        while (i + 1 < size() && !(weights_[i] > 0)) ++i;
        while (i > 0 && !(weights_[i] > 0)) --i;
        return i;
    }

    /// The last i in [first, last) with !(u < cdf_[i]), or `first` if there is none, found
    /// without branches: the samples' u are random, and mispredicted branches would cost more
    /// than the search.
    size_t lastAtMost(double u, size_t first, size_t last) const {
        const double* base = cdf_.data() + first;
        for (size_t len = last - first; len > 1;) {
            size_t half = len / 2;
            base = u < base[half] ? base : base + half;
            len -= half;
        }
        return static_cast<size_t>(base - cdf_.data());
    }

    std::vector<double> weights_;
    std::vector<double> cdf_;
    std::vector<uint32_t> guide_;  ///< n + 1 entries: guide_[k] = lastAtMost(k / n).
    double total_ = 0;
};

/// A piecewise-constant density on the unit square [0, 1)^2 over a grid of nx columns by ny
/// rows of weights (>= 0): cell (x, y) covers [x / nx, (x + 1) / nx) x [y / ny, (y + 1) / ny)
/// and has density weight(x, y) nx ny / sum. Sampled pbrt's way: a row by the marginal
/// distribution of the rows' sums, then a column by that row's conditional distribution. If
/// every weight is 0 (or the sum is not finite), it is uniform.
class Distribution2D {
  public:
    Distribution2D() = default;

    /// Weights row by row: `weights[y * nx + x]` is cell (x, y).
    Distribution2D(const std::vector<double>& weights, size_t nx, size_t ny)
        : Distribution2D(nx, ny, [&](size_t y) {
              auto row = weights.begin() + static_cast<std::ptrdiff_t>(y * nx);
              return std::vector<double>(row, row + static_cast<std::ptrdiff_t>(nx));
          }) {}

    /// Weights from `rowWeights(y)`, a std::vector<double> of nx weights for row y, called once
    /// per row in order: so that a large grid needs no array of all its weights at once.
    template <typename RowWeights>
    Distribution2D(size_t nx, size_t ny, RowWeights rowWeights) {
        rows_.reserve(ny);
        std::vector<double> sums(ny);
        for (size_t y = 0; y < ny; ++y) {
            std::vector<double> row = rowWeights(y);
            row.resize(nx, 0.0);  // a short row's missing cells weigh nothing
            double sum = 0;
            for (double w : row) sum += w > 0 && std::isfinite(w) ? w : 0.0;
            sums[y] = sum;
            rows_.emplace_back(std::move(row));
        }
        marginal_ = Distribution1D(std::move(sums));
    }

    size_t width() const { return rows_.empty() ? 0 : rows_.front().size(); }
    size_t height() const { return rows_.size(); }

    /// A point of [0, 1)^2 drawn with `u` in [0, 1)^2 (u.y picks the row, u.x the column
    /// within it), and its density over the unit square; `column` and `row` receive its cell
    /// (which rounding of the point's coordinates might not give back at a cell's edge).
    Point2 sample(Point2 u, double* density = nullptr, size_t* column = nullptr,
                  size_t* row = nullptr) const {
        double rowDensity = 0, columnDensity = 0;
        size_t r = 0, c = 0;
        double y = marginal_.sampleContinuous(u.y, &rowDensity, &r);
        double x = rows_[r].sampleContinuous(u.x, &columnDensity, &c);
        if (density) *density = rowDensity * columnDensity;
        if (column) *column = c;
        if (row) *row = r;
        return {x, y};
    }

    /// The density of sample() at `p` (coordinates outside [0, 1) read as the nearest cell).
    double density(Point2 p) const {
        size_t row = std::min(
            static_cast<size_t>(std::max(p.y, 0.0) * static_cast<double>(height())), height() - 1);
        double rowDensity = marginal_.density(p.y);
        return rowDensity > 0 ? rowDensity * rows_[row].density(p.x) : 0.0;
    }

  private:
    std::vector<Distribution1D> rows_;  ///< The conditional distribution of each row.
    Distribution1D marginal_;           ///< Of the rows, by their sums.
};

}  // namespace glint
