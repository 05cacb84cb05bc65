#pragma once
// What the BSDF tests share: chi-square tests of sample() against pdf() over the sphere of
// directions, and directional albedos (white furnaces).

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <numbers>
#include <optional>
#include <vector>

#include "glint/math/rng.h"
#include "glint/render/bsdfs/bsdf.h"
#include "unit/statistics.h"

namespace glint::test {

constexpr double kPi = std::numbers::pi;

/// The unit direction at polar angle theta and azimuth phi (degrees) about +z.
inline Vec3 direction(double thetaDegrees, double phiDegrees = 30) {
    double t = thetaDegrees * kPi / 180, p = phiDegrees * kPi / 180;
    return {std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t)};
}

inline Point2 uniform2(Rng& rng) { return {rng.uniform(), rng.uniform()}; }

// ---- Chi-square tests of sample() against pdf() ----

/// Pearson's test over (cos theta, phi) bins of the whole sphere, plus one bin for the draws
/// that give no direction with a density (none, or a delta lobe), whose expected share is
/// 1 - the integral of pdf.
constexpr int kCosBins = 20, kPhiBins = 40;
constexpr long kSamples = 1'000'000;
/// Probability of any false failure among the chi-square tests below.
constexpr double kAlpha = 0.01;

inline int binOf(const Vec3& w) {
    int c = std::clamp(static_cast<int>((w.z + 1) / 2 * kCosBins), 0, kCosBins - 1);
    double phi = std::atan2(w.y, w.x);
    if (phi < 0) phi += 2 * kPi;
    int p = std::clamp(static_cast<int>(phi / (2 * kPi) * kPhiBins), 0, kPhiBins - 1);
    return c * kPhiBins + p;
}

struct ChiSquareRun {
    test::ChiSquareResult result;
    double worstMismatch = 0;  ///< Largest relative difference of a sample's f, pdf from eval, pdf.
};

/// A density over the sphere of directions wi, 1 / sr.
using Density = std::function<double(const Vec3& wi)>;

/// Draws kSamples directions from `sampler` for `wo` and tests them against `density` (the
/// sampler's own pdf, except when a test checks that a wrong density is caught).
inline ChiSquareRun chiSquare(const Bsdf& sampler, const Density& density, const Vec3& wo,
                              uint64_t seed) {
    const int bins = kCosBins * kPhiBins;
    std::vector<double> observed(bins + 1, 0), expected(bins + 1, 0);
    ChiSquareRun run;
    auto relative = [](double a, double b) {
        return std::abs(a - b) / std::max(std::abs(b), 1e-300);
    };
    Rng rng(seed);
    for (long k = 0; k < kSamples; ++k) {
        double uc = rng.uniform();
        std::optional<BsdfSample> s = sampler.sample(wo, uc, uniform2(rng));
        if (!s || s->isSpecular()) {
            observed[bins] += 1;
            continue;
        }
        observed[binOf(s->wi)] += 1;
        Vec3 f = sampler.eval(wo, s->wi);
        double worst = std::max({relative(s->pdf, sampler.pdf(wo, s->wi)), relative(s->f.x, f.x),
                                 relative(s->f.y, f.y), relative(s->f.z, f.z)});
        run.worstMismatch = std::max(run.worstMismatch, worst);
    }
    double inside = 0;
    for (int c = 0; c < kCosBins; ++c)
        for (int p = 0; p < kPhiBins; ++p) {
            double c0 = -1 + 2.0 * c / kCosBins, c1 = -1 + 2.0 * (c + 1) / kCosBins;
            double p0 = 2 * kPi * p / kPhiBins, p1 = 2 * kPi * (p + 1) / kPhiBins;
            auto overPhi = [&](double cosTheta) {
                double sinTheta = std::sqrt(std::max(0.0, 1 - cosTheta * cosTheta));
                auto pdf = [&](double phi) {
                    Vec3 wi(sinTheta * std::cos(phi), sinTheta * std::sin(phi), cosTheta);
                    return density(wi);
                };
                return test::integrate(pdf, p0, p1, 1e-10);
            };
            // d(solid angle) = d(cos theta) d(phi).
            double mass = test::integrate(overPhi, c0, c1, 1e-8);
            expected[c * kPhiBins + p] = mass * kSamples;
            inside += mass;
        }
    expected[bins] = std::max(0.0, 1 - inside) * kSamples;
    run.result = test::chiSquareTest(observed, expected);
    return run;
}
/// ... against the density of `density` for `wo`.
inline ChiSquareRun chiSquare(const Bsdf& sampler, const Bsdf& density, const Vec3& wo,
                              uint64_t seed) {
    return chiSquare(
        sampler, [&](const Vec3& wi) { return density.pdf(wo, wi); }, wo, seed);
}

/// The directional albedo for `wo`, per channel, from n samples.
inline std::array<test::MeanEstimate, 3> albedo(const Bsdf& bsdf, const Vec3& wo, long n,
                                                uint64_t seed) {
    std::array<test::MeanEstimate, 3> e;
    Rng rng(seed);
    for (long k = 0; k < n; ++k) {
        double uc = rng.uniform();
        std::optional<BsdfSample> s = bsdf.sample(wo, uc, uniform2(rng));
        Vec3 w = s ? s->weight() : Vec3(0);
        for (int c = 0; c < 3; ++c) e[c].add(w[c]);
    }
    return e;
}

}  // namespace glint::test
