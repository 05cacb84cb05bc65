#include "glint/render/bsdfs/thin_film.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace glint {
namespace {

constexpr double kPi = std::numbers::pi;

double schlick(double f0, double c) {
    const double m = std::clamp(1 - c, 0.0, 1.0);
    return f0 + (1 - f0) * (m * m) * (m * m) * m;
}

/// The normal-incidence reflectance between indices a and b.
double f0Of(double a, double b) {
    const double r = (a - b) / (a + b);
    return r * r;
}

/// The index a base of normal-incidence reflectance f0 has against air.
double iorOf(double f0) {
    const double s = std::sqrt(std::clamp(f0, 0.0, 0.9999));
    return (1 + s) / (1 - s);
}

/// The Fourier transform of the colour matching functions at optical path difference `opd`
/// (nanometres) and phase `shift`, in linear Rec. 709 RGB: Belcour and Barla's Gaussian fits
/// of x, y and z (x has two lobes), normalised as they are.
Vec3 sensitivity(double opd, const Vec3& shift) {
    const double phase = 2 * kPi * opd * 1e-9;
    const double val[3] = {5.4856e-13, 4.4201e-13, 5.2481e-13};
    const double pos[3] = {1.6810e+06, 1.7953e+06, 2.2084e+06};
    const double var[3] = {4.3278e+09, 9.3046e+09, 6.6121e+09};
    double xyz[3];
    for (int c = 0; c < 3; ++c)
        xyz[c] = val[c] * std::sqrt(2 * kPi * var[c]) * std::cos(pos[c] * phase + shift[c]) *
                 std::exp(-phase * phase * var[c]);
    xyz[0] += 9.7470e-14 * std::sqrt(2 * kPi * 4.5282e+09) *
              std::cos(2.2399e+06 * phase + shift[0]) * std::exp(-4.5282e+09 * phase * phase);
    for (double& v : xyz) v /= 1.0685e-7;
    // CIE XYZ to linear Rec. 709 (sRGB primaries, D65).
    return {3.2404542 * xyz[0] - 1.5371385 * xyz[1] - 0.4985314 * xyz[2],
            -0.9692660 * xyz[0] + 1.8760108 * xyz[1] + 0.0415560 * xyz[2],
            0.0556434 * xyz[0] - 0.2040259 * xyz[1] + 1.0572252 * xyz[2]};
}

}  // namespace

Vec3 thinFilmReflectance(double cosTheta, double filmIor, double thickness, const Vec3& baseF0) {
    cosTheta = std::clamp(cosTheta, 0.0, 1.0);
    // No film at thickness 0 (the specification's smoothstep over 0.03 nm).
    const double fade = std::clamp(thickness / 0.03, 0.0, 1.0);
    const double eta2 = 1 + (filmIor - 1) * fade * fade * (3 - 2 * fade);
    const double sin2 = (1 / eta2) * (1 / eta2) * (1 - cosTheta * cosTheta);
    const double cos2sq = 1 - sin2;
    if (cos2sq < 0) return Vec3(1);  // total internal reflection
    const double cos2 = std::sqrt(cos2sq);
    // First interface, air to film.
    const double r12 = schlick(f0Of(eta2, 1), cosTheta);
    const double t121 = 1 - r12;
    const double phi12 = eta2 < 1 ? kPi : 0, phi21 = kPi - phi12;
    Vec3 out;
    const double opd = 2 * eta2 * thickness * cos2;
    double r23[3], phi23[3];
    for (int c = 0; c < 3; ++c) {
        const double eta3 = iorOf(baseF0[c]);
        r23[c] = schlick(f0Of(eta3, eta2), cos2);
        phi23[c] = eta3 < eta2 ? kPi : 0;
    }
    const Vec3 phi(phi21 + phi23[0], phi21 + phi23[1], phi21 + phi23[2]);
    Vec3 cm, sum;
    double r123[3];
    for (int c = 0; c < 3; ++c) {
        const double r = std::clamp(r12 * r23[c], 1e-5, 0.9999);
        r123[c] = std::sqrt(r);
        const double rs = t121 * t121 * r23[c] / (1 - r);
        sum[c] = r12 + rs;  // the incoherent part
        cm[c] = rs - t121;
    }
    for (int m = 1; m <= 2; ++m) {
        const Vec3 s = sensitivity(m * opd, phi * static_cast<double>(m)) * 2.0;
        for (int c = 0; c < 3; ++c) {
            cm[c] *= r123[c];
            sum[c] += cm[c] * s[c];
        }
    }
    for (int c = 0; c < 3; ++c) out[c] = std::clamp(sum[c], 0.0, 1.0);
    return out;
}

}  // namespace glint
