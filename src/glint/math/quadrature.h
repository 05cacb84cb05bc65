#pragma once
/// Numerical integration for checks and generated tables (never in a render's inner loop).

#include <cmath>

namespace glint {

/// The integral of f over [a, b] by adaptive Simpson quadrature to about `tolerance`
/// (absolute), the interval first cut into `pieces` so that narrow peaks are not missed, each
/// piece halved at most `depth` times.
template <typename F>
double integrateAdaptive(const F& f, double a, double b, double tolerance, int pieces = 4,
                         int depth = 24) {
    struct Simpson {
        const F& f;
        double step(double a, double fa, double b, double fb, double m, double fm, double whole,
                    double tol, int depth) const {
            double lm = 0.5 * (a + m), rm = 0.5 * (m + b);
            double flm = f(lm), frm = f(rm);
            double left = (m - a) / 6 * (fa + 4 * flm + fm);
            double right = (b - m) / 6 * (fm + 4 * frm + fb);
            double diff = left + right - whole;
            if (depth <= 0 || std::abs(diff) <= 15 * tol) return left + right + diff / 15;
            return step(a, fa, m, fm, lm, flm, left, tol / 2, depth - 1) +
                   step(m, fm, b, fb, rm, frm, right, tol / 2, depth - 1);
        }
    };
    Simpson s{f};
    double sum = 0, h = (b - a) / pieces;
    for (int k = 0; k < pieces; ++k) {
        double x0 = a + k * h, x1 = k + 1 == pieces ? b : x0 + h, xm = 0.5 * (x0 + x1);
        double f0 = f(x0), f1 = f(x1), fm = f(xm);
        double whole = (x1 - x0) / 6 * (f0 + 4 * fm + f1);
        sum += s.step(x0, f0, x1, f1, xm, fm, whole, tolerance / pieces, depth);
    }
    return sum;
}

}  // namespace glint
