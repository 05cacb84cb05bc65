#pragma once
/// The directional albedo of Glint's GGX reflection lobe with Fresnel reflectance 1, for the
/// multiple-scattering compensation of the rough conductor (bsdf.h):
///     E(mu, alpha) = integral over the hemisphere of D(h) G1(wo) G1(wi) / (4 mu) cos_i dwi,
/// mu = cos theta_o, with optics.h's GGX D and separable Smith G1 (not the height-correlated
/// masking of other renderers, whose E differs), and its cosine-weighted hemispherical average
///     E_avg(alpha) = 2 integral_0^1 E(mu, alpha) mu dmu.
///
/// E is looked up in a table (ggx_albedo_table.cpp) that tools/ggx_albedo_table.cpp computes by
/// adaptive quadrature and writes; the layout below is shared by the two. Generated offline
/// rather than in-process on first use: the table's 3000 entries are 2D integrals whose
/// integrand has a kink (where wi crosses the horizon) and, for smooth surfaces, all its
/// variation in a thin rim of the disk of visible normals; accurate to 1e-8, they take the
/// generator 25 s, while a fixed rule cheap enough for first use (a 16 x 32-point Gauss rule
/// per entry, about 50 ms in all) errs by up to 3e-3 where alpha is small, five times the
/// interpolation's error. A unit test recomputes entries by an independent quadrature, so a
/// table that no longer matches optics.h fails.
///
/// Layout: 96 rows of 32 columns, dense where E changes fast.
///  - Row 0 is alpha = 0 (E = 1: the mirror loses nothing); rows 1 to kRows - 1 are spaced
///    geometrically from alpha = kAlpha1 = 1e-3 to 1 (7.6% apart). Near alpha = 0, E(mu, alpha)
///    is a function of mu / alpha (a dip of 10 to 15% at grazing angles, mu ~ alpha), so
///    evenly spaced rows would leave the dip of every small alpha between two of them. Below
///    row 1 the compensation fades linearly to none at alpha = 0: the error there is up to
///    kMaxErrorBelowRow1 = 0.068, but above 1.2e-3 only within 0.6 degrees of grazing.
///  - Each row has its own columns, uniform in s = w / (w + c alpha (1 - w)), alpha the row's
///    roughness, w = 1 - sqrt(1 - mu) (mu / 2 near grazing, 1 - theta / sqrt(2) near the
///    normal), c = kColumnScale: for small alpha the columns crowd into the grazing dip, and
///    for alpha = 1 they are nearly even in w, so even in the angle near the normal (E has a
///    corner at normal incidence, linear in theta_o, which even steps in mu would smear).
///
/// Interpolation: linear in s within a row, and between the two rows about alpha linear in the
/// row coordinate, each row read in its own columns. So E at a given alpha is a fixed blend of
/// two row functions, and its average is the same blend of the rows' averages (kAverage): the
/// E_avg returned is the exact average of the E returned, which the compensation's white
/// furnace needs (bsdf.cpp). The generator measures the table's error |E_table - E| at every
/// cell's centre and edge midpoints: at most kMaxError = 6.2e-4 for alpha >= 1e-3 (largest
/// near normal incidence at alpha ~ 0.3; 2.9e-4 below alpha = 0.1).

#include <algorithm>
#include <cmath>
#include <numbers>

namespace glint {

namespace ggx_albedo_table {

inline constexpr int kRows = 96;
inline constexpr int kColumns = 32;
/// The roughness of row 1; rows 1 to kRows - 1 are spaced geometrically from it to 1.
inline constexpr double kAlpha1 = 1e-3;

/// c of the columns' spacing.
inline constexpr double kColumnScale = 0.8;

/// The roughness of row r (fractional rows give the roughness between).
inline double rowAlpha(double r) {
    if (r <= 1) return r * kAlpha1;
    return kAlpha1 * std::pow(1 / kAlpha1, (r - 1) / (kRows - 2));
}
/// The (fractional) row of roughness alpha, in [0, kRows - 1].
inline double rowOf(double alpha) {
    alpha = std::clamp(alpha, 0.0, 1.0);
    if (alpha <= kAlpha1) return alpha / kAlpha1;
    return 1 + (kRows - 2) * std::log(alpha / kAlpha1) / std::log(1 / kAlpha1);
}

/// w = 1 - sqrt(1 - mu), the columns' measure of the direction at mu = cos theta: like the
/// elevation above the surface (mu / 2 near grazing, 1 - theta / sqrt(2) near the normal) for
/// the price of a square root.
inline double measureOf(double mu) { return 1 - std::sqrt(1 - std::clamp(mu, 0.0, 1.0)); }

/// The (fractional) column in [0, kColumns - 1] of measure w in the row of roughness alpha > 0.
inline double columnOf(double w, double alpha) {
    double d = w + kColumnScale * alpha * (1 - w);
    return (d > 0 ? w / d : 0) * (kColumns - 1);
}
/// The measure w of column j (fractional) in the row of roughness alpha > 0.
inline double columnMeasure(double j, double alpha) {
    double s = j / (kColumns - 1), ca = kColumnScale * alpha;
    return s * ca / (1 - s + s * ca);
}
/// mu = cos theta of column j (fractional) in the row of roughness alpha > 0.
inline double columnCosine(double j, double alpha) {
    double w = columnMeasure(j, alpha);
    return w * (2 - w);
}

/// Row `row` of `table` (kColumns values, for roughness `alpha`) at measure `w`.
inline double rowValue(const float* row, double alpha, double w) {
    if (alpha == 0) return row[0];  // the mirror's row: constant
    double x = columnOf(w, alpha);
    int j = std::clamp(static_cast<int>(x), 0, kColumns - 2);
    double t = std::clamp(x - j, 0.0, 1.0);
    return (1 - t) * row[j] + t * row[j + 1];
}

/// rowAlpha(r) of each row (written by the generator, so that lookups need no pow()).
extern const double kRowAlpha[kRows];
/// E(mu, alpha), per row and column: written by tools/ggx_albedo_table.cpp.
extern const float kAlbedo[kRows][kColumns];
/// 2 integral_0^1 E_r(mu) mu dmu of each row as interpolated (not of the true E).
extern const double kAverage[kRows];
/// The largest |E_table - E| the generator found (cell centres and edge midpoints) for alpha
/// >= kAlpha1, and below it (where the compensation fades out; large at grazing angles only).
extern const double kMaxError;
extern const double kMaxErrorBelowRow1;

}  // namespace ggx_albedo_table

/// E(mu) and E_avg for one roughness alpha in [0, 1] (clamped), from the table.
class GgxAlbedo {
  public:
    explicit GgxAlbedo(double alpha) {
        using namespace ggx_albedo_table;
        double r = rowOf(alpha);
        row_ = std::clamp(static_cast<int>(r), 0, kRows - 2);
        weight_ = std::clamp(r - row_, 0.0, 1.0);
        alpha0_ = kRowAlpha[row_];
        alpha1_ = kRowAlpha[row_ + 1];
        average_ = (1 - weight_) * kAverage[row_] + weight_ * kAverage[row_ + 1];
    }

    /// E(mu) for mu = cos theta_o in [0, 1] (clamped).
    double operator()(double mu) const {
        using namespace ggx_albedo_table;
        double w = measureOf(mu);
        return (1 - weight_) * rowValue(kAlbedo[row_], alpha0_, w) +
               weight_ * rowValue(kAlbedo[row_ + 1], alpha1_, w);
    }
    /// E_avg: the exact cosine-weighted average of operator() over the hemisphere.
    double average() const { return average_; }

  private:
    int row_ = 0;
    double weight_ = 0, alpha0_ = 0, alpha1_ = 0, average_ = 1;
};

}  // namespace glint
