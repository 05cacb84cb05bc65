#pragma once
// Statistics for the tests of sampling code: Pearson's chi-square goodness-of-fit test with its
// p-value, the Sidak correction for many tests, and adaptive numerical integration (for the
// expected counts, independently of the samplers under test).

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

#include "glint/math/quadrature.h"

namespace glint::test {

/// The regularized upper incomplete gamma function Q(a, x) = Gamma(a, x) / Gamma(a), for
/// a > 0, x >= 0: by its power series below x = a + 1 and by its continued fraction above
/// (Abramowitz and Stegun 6.5.29 and 6.5.31, the fraction evaluated by Lentz's method).
inline double gammaQ(double a, double x) {
    if (x <= 0) return 1;
    double logPrefix = a * std::log(x) - x - std::lgamma(a);
    if (x < a + 1) {
        // P(a, x) = x^a e^-x / Gamma(a + 1) * sum_n x^n / ((a + 1) ... (a + n)).
        double term = 1 / a, sum = term;
        for (int n = 1; n < 10000 && term > sum * 1e-17; ++n) {
            term *= x / (a + n);
            sum += term;
        }
        return 1 - std::exp(logPrefix) * sum;
    }
    // Q(a, x) = x^a e^-x (1 / (x + 1 - a - 1 (1 - a) / (x + 3 - a - 2 (2 - a) / (x + 5 - a ...
    const double tiny = 1e-300;
    double b = x + 1 - a, c = 1 / tiny, d = 1 / b, h = d;
    for (int n = 1; n < 10000; ++n) {
        double an = -n * (n - a);
        b += 2;
        d = an * d + b;
        if (std::abs(d) < tiny) d = tiny;
        c = b + an / c;
        if (std::abs(c) < tiny) c = tiny;
        d = 1 / d;
        double delta = d * c;
        h *= delta;
        if (std::abs(delta - 1) < 1e-16) break;
    }
    return std::exp(logPrefix) * h;
}

/// The probability that a chi-square variable of `dof` degrees of freedom exceeds `chi2`.
inline double chiSquarePValue(double chi2, int dof) { return gammaQ(0.5 * dof, 0.5 * chi2); }

/// The significance level of each of `tests` independent tests for which the probability of
/// any false rejection is `alpha` (Sidak's correction): 1 - (1 - alpha)^(1 / tests).
inline double sidak(double alpha, int tests) { return 1 - std::pow(1 - alpha, 1.0 / tests); }

struct ChiSquareResult {
    double chi2 = 0;
    int dof = 0;
    double pValue = 1;
    int bins = 0;  ///< After pooling.
    /// A bin where nothing was expected received samples: the sampler leaves the density's
    /// support (pValue is then 0).
    bool outsideSupport = false;
};

/// Pearson's test of `observed` counts against `expected` ones (the same total). Bins expected
/// to receive fewer than `minExpected` samples are pooled, smallest first, into groups that
/// reach it (a partition fixed by the expectations alone, so the statistic keeps its
/// distribution); a last group short of it joins the smallest full bin.
inline ChiSquareResult chiSquareTest(const std::vector<double>& observed,
                                     const std::vector<double>& expected, double minExpected = 5) {
    ChiSquareResult r;
    double total = std::accumulate(expected.begin(), expected.end(), 0.0);
    std::vector<size_t> order(expected.size());
    std::iota(order.begin(), order.end(), size_t{0});
    std::sort(order.begin(), order.end(),
              [&](size_t a, size_t b) { return expected[a] < expected[b]; });
    std::vector<double> obs, exp;
    double poolObs = 0, poolExp = 0;
    for (size_t k : order) {
        if (expected[k] <= 1e-12 * total && observed[k] > 0) r.outsideSupport = true;
        if (expected[k] >= minExpected && poolExp == 0) {
            obs.push_back(observed[k]);
            exp.push_back(expected[k]);
            continue;
        }
        poolObs += observed[k];
        poolExp += expected[k];
        if (poolExp >= minExpected) {
            obs.push_back(poolObs);
            exp.push_back(poolExp);
            poolObs = poolExp = 0;
        }
    }
    if (poolExp > 0 || poolObs > 0) {
        if (exp.empty()) {
            obs.push_back(poolObs);
            exp.push_back(poolExp);
        } else {
            obs.front() += poolObs;  // the smallest group that reached minExpected
            exp.front() += poolExp;
        }
    }
    for (size_t k = 0; k < obs.size(); ++k) {
        double d = obs[k] - exp[k];
        r.chi2 += d * d / exp[k];
    }
    r.bins = static_cast<int>(obs.size());
    r.dof = std::max(1, r.bins - 1);
    r.pValue = r.outsideSupport ? 0 : chiSquarePValue(r.chi2, r.dof);
    return r;
}

/// The integral of f over [a, b] by adaptive Simpson quadrature to about `tolerance`
/// (absolute), the interval first cut into `pieces` so that narrow peaks are not missed.
template <typename F>
double integrate(const F& f, double a, double b, double tolerance, int pieces = 4) {
    return integrateAdaptive(f, a, b, tolerance, pieces, 24);
}

/// Mean and standard error of a sample of values.
struct MeanEstimate {
    double sum = 0, sum2 = 0;
    long n = 0;

    void add(double v) {
        sum += v;
        sum2 += v * v;
        ++n;
    }
    double mean() const { return sum / static_cast<double>(n); }
    double standardError() const {
        double m = mean(), count = static_cast<double>(n);
        return std::sqrt(std::max(0.0, sum2 / count - m * m) / (count - 1));
    }
};

}  // namespace glint::test
