#include "glint/render/bsdfs/sheen.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace glint {
namespace {

/// Estevez and Kulla's fit of log Lambda over cos theta: a / (1 + b x^c) + d x + e, the
/// coefficients at alpha = 0 and alpha = 1 (their table), blended by (1 - alpha)^2.
double lambdaFit(double x, double alpha) {
    const double t = (1 - alpha) * (1 - alpha);
    auto mix = [t](double at1, double at0) { return at1 + (at0 - at1) * t; };
    const double a = mix(21.5473, 25.3245), b = mix(3.82987, 3.32435), c = mix(0.19823, 0.16801),
                 d = mix(-1.97760, -1.27393), e = mix(-4.32054, -4.85967);
    return a / (1 + b * std::pow(x, c)) + d * x + e;
}

/// Their Lambda, with the fit mirrored about cos theta = 0.5 so that it stays smooth.
double lambda(double cosTheta, double alpha) {
    const double x = std::clamp(cosTheta, 0.0, 1.0);
    if (x < 0.5) return std::exp(lambdaFit(x, alpha));
    return std::exp(2 * lambdaFit(0.5, alpha) - lambdaFit(1 - x, alpha));
}

}  // namespace

double sheenLobe(double alpha, const Vec3& o, const Vec3& i) {
    if (!(o.z > 0) || !(i.z > 0)) return 0;
    alpha = std::clamp(alpha, kMinSheenAlpha, 1.0);
    const Vec3 h = normalize(o + i);
    const double sin2 = std::max(0.0, 1 - h.z * h.z);
    const double inv = 1 / alpha;
    const double d = (2 + inv) * std::pow(sin2, 0.5 * inv) / (2 * std::numbers::pi);
    const double v = 1 / ((1 + lambda(o.z, alpha) + lambda(i.z, alpha)) * 4 * o.z * i.z);
    return d * v;
}

double sheenAlbedoByQuadrature(double alpha, double mu, int steps) {
    mu = std::clamp(mu, 1e-4, 1.0);
    const Vec3 o(std::sqrt(1 - mu * mu), 0, mu);
    // Midpoints in theta_i (the lobe is brightest towards grazing angles, where cos theta
    // crowds) and in phi over [0, pi], doubled by the lobe's symmetry about the plane of o.
    double sum = 0;
    const double dTheta = std::numbers::pi / 2 / steps, dPhi = std::numbers::pi / (2 * steps);
    for (int t = 0; t < steps; ++t) {
        const double theta = (t + 0.5) * dTheta;
        const double st = std::sin(theta), ct = std::cos(theta);
        for (int p = 0; p < 2 * steps; ++p) {
            const double phi = (p + 0.5) * dPhi;
            const Vec3 i(st * std::cos(phi), st * std::sin(phi), ct);
            sum += sheenLobe(alpha, o, i) * ct * st;
        }
    }
    return 2 * sum * dTheta * dPhi;
}

namespace sheen_albedo_table {

double rowAlpha(int r) {
    const double r0 = std::sqrt(kMinSheenAlpha);
    const double p = r0 + (1 - r0) * r / (kRows - 1.0);
    return p * p;
}

double columnMu(int c) {
    const double s = c / (kColumns - 1.0);
    return s * s;
}

}  // namespace sheen_albedo_table

double sheenAlbedo(double alpha, double mu) {
    using namespace sheen_albedo_table;
    const double root0 = std::sqrt(kMinSheenAlpha);
    const double r = std::clamp((std::sqrt(alpha) - root0) / (1 - root0), 0.0, 1.0) * (kRows - 1);
    const double c = std::sqrt(std::clamp(mu, 0.0, 1.0)) * (kColumns - 1);
    const int r0 = std::min(static_cast<int>(r), kRows - 2);
    const int c0 = std::min(static_cast<int>(c), kColumns - 2);
    const double fr = r - r0, fc = c - c0;
    auto at = [&](int rr, int cc) { return static_cast<double>(kE[rr * kColumns + cc]); };
    const double top = at(r0, c0) + (at(r0, c0 + 1) - at(r0, c0)) * fc;
    const double bottom = at(r0 + 1, c0) + (at(r0 + 1, c0 + 1) - at(r0 + 1, c0)) * fc;
    return top + (bottom - top) * fr;
}

}  // namespace glint
