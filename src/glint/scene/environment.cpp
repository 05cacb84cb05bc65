#include "glint/scene/environment.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "glint/scene/light_spec.h"

namespace glint {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kInvPi = std::numbers::inv_pi;
constexpr double kInv2Pi = 0.5 * std::numbers::inv_pi;

/// A texel value as radiance: NaN and negative values read as 0, large ones as kMaxRadiance.
float cleanTexel(float v) {
    if (!(v > 0)) return 0;
    return v < static_cast<float>(kMaxRadiance) ? v : static_cast<float>(kMaxRadiance);
}

/// 1 - cos(pi k / h): the solid angle over 2 pi of the cap above row edge k (of 0 to h), as
/// 2 sin^2 so that caps near the poles keep their precision.
double capArea(int k, int h) {
    double half = std::sin(kPi * k / (2.0 * h));
    return 2 * half * half;
}

/// cos(theta0) - cos(theta1) for row y's band theta0 = pi y / h to theta1 = pi (y + 1) / h,
/// written as a product so that the thin bands at the poles keep their precision: the row's
/// solid angle over 2 pi.
double rowBand(int y, int h) {
    return 2 * std::sin(kPi * (2 * y + 1) / (2.0 * h)) * std::sin(kPi / (2.0 * h));
}

/// The mean over the sphere of `map`'s bilinear radiance (before its scale), exactly. Across a
/// row the interpolation keeps the row's mean; down the image it interpolates the rows' means
/// between row centres t_y = (y + 1/2) / h, constant above the first and below the last. The
/// mean is (pi / 2) integral of R(t) sin(pi t) dt, as d omega = 2 pi^2 sin(pi t) ds dt.
Vec3 meanOverSphere(const EnvironmentMap& map) {
    const int w = map.width(), h = map.height();
    std::vector<double> rowWeight(static_cast<size_t>(h), 0.0);
    auto centre = [&](int y) { return kPi * (y + 0.5) / h; };  // pi t_y
    rowWeight.front() += (1 - std::cos(centre(0))) / kPi;
    rowWeight.back() += (1 + std::cos(centre(h - 1))) / kPi;
    for (int y = 0; y + 1 < h; ++y) {
        // Over [t_y, t_y+1], row y weighs (t_y+1 - t) / (t_y+1 - t_y), row y + 1 the rest.
        double a = centre(y), b = centre(y + 1);
        double whole = (std::cos(a) - std::cos(b)) / kPi;
        double falling = std::cos(a) / kPi + (std::sin(a) - std::sin(b)) / (kPi * (b - a));
        rowWeight[static_cast<size_t>(y)] += falling;
        rowWeight[static_cast<size_t>(y) + 1] += whole - falling;
    }
    Vec3 sum(0);
    for (int y = 0; y < h; ++y) {
        Vec3 row(0);
        for (int x = 0; x < w; ++x) row += map.texel(x, y);
        sum += row * (rowWeight[static_cast<size_t>(y)] * kPi / 2 / w);
    }
    return sum;
}

/// The texels' sampling weights: the mean of the bilinear luminance over each texel's cell
/// times the cell's solid angle (2 pi / w x `bands`[y]). Over a cell, bilinear interpolation
/// between texel centres weights the texel and its neighbours by [1/8, 3/4, 1/8] on each axis
/// (wrapped around horizontally, clamped vertically, as eval() reads them), so a cell has
/// weight > 0 wherever eval() can return radiance inside it. Rows are built one at a time.
Distribution2D samplingDistribution(const EnvironmentMap& map, const std::vector<double>& bands) {
    const int w = map.width(), h = map.height();
    auto filteredRow = [&](int y) {  // [1/8, 3/4, 1/8] across row y's luminance
        std::vector<double> lum(static_cast<size_t>(w)), out(static_cast<size_t>(w));
        for (int x = 0; x < w; ++x) lum[static_cast<size_t>(x)] = luminance(map.texel(x, y));
        for (int x = 0; x < w; ++x) {
            size_t left = static_cast<size_t>(x == 0 ? w - 1 : x - 1);
            size_t right = static_cast<size_t>(x == w - 1 ? 0 : x + 1);
            out[static_cast<size_t>(x)] =
                0.75 * lum[static_cast<size_t>(x)] + 0.125 * (lum[left] + lum[right]);
        }
        return out;
    };
    std::vector<double> here = filteredRow(0), above = here,
                        below = filteredRow(std::min(1, h - 1));
    return Distribution2D(static_cast<size_t>(w), static_cast<size_t>(h), [&](size_t row) {
        const int y = static_cast<int>(row);
        if (y > 0) {
            above = std::move(here);
            here = std::move(below);
            below = filteredRow(std::min(y + 1, h - 1));
        }
        std::vector<double> weights(here.size());
        for (size_t x = 0; x < weights.size(); ++x)
            weights[x] = bands[row] * (0.75 * here[x] + 0.125 * (above[x] + below[x]));
        return weights;
    });
}

}  // namespace

EnvironmentMap::EnvironmentMap(int width, int height, std::vector<float> rgb, double scale,
                               double rotationDegrees)
    : width_(width),
      height_(height),
      rgb_(std::move(rgb)),
      scale_(scale),
      rotationDegrees_(rotationDegrees) {
    if (width < 1 || height < 1)
        throw std::invalid_argument("environment map of " + std::to_string(width) + " x " +
                                    std::to_string(height) + " texels");
    const size_t texels = static_cast<size_t>(width) * static_cast<size_t>(height);
    if (rgb_.size() != texels * 3)
        throw std::invalid_argument("environment map of " + std::to_string(width) + " x " +
                                    std::to_string(height) + " texels given " +
                                    std::to_string(rgb_.size()) + " floats");
    if (!(scale >= 0 && std::isfinite(scale)))
        throw std::invalid_argument("environment map scale must be finite and >= 0");
    if (!std::isfinite(rotationDegrees))
        throw std::invalid_argument("environment map rotation must be finite");
    double turns = rotationDegrees / 360;
    rotationTurns_ = turns - std::floor(turns);

    for (float& v : rgb_) v = cleanTexel(v);
    bands_.resize(static_cast<size_t>(height));
    for (int y = 0; y < height; ++y) bands_[static_cast<size_t>(y)] = rowBand(y, height);

    average_ = meanOverSphere(*this);
    distribution_ = samplingDistribution(*this, bands_);
}

Point2 EnvironmentMap::imageCoordinates(const Vec3& dir) const {
    double s = 0.5 + std::atan2(dir.z, dir.x) * kInv2Pi + rotationTurns_;
    s -= std::floor(s);
    if (!(s >= 0 && s < 1)) s = 0;  // 1 by rounding (a tiny negative s), or NaN
    double t = std::atan2(std::sqrt(dir.x * dir.x + dir.z * dir.z), dir.y) * kInvPi;
    if (!(t >= 0)) t = 0;
    return {s, std::min(t, 1.0)};
}

Vec3 EnvironmentMap::direction(Point2 st) const {
    double theta = kPi * st.y;
    double phi = 2 * kPi * (st.x - rotationTurns_) - kPi;
    double sinTheta = std::sin(theta);
    return {sinTheta * std::cos(phi), std::cos(theta), sinTheta * std::sin(phi)};
}

Vec3 EnvironmentMap::eval(const Vec3& dir) const { return evalAt(imageCoordinates(dir)); }

Vec3 EnvironmentMap::evalAt(Point2 st) const {
    // Texel centres sit at (x + 1/2) / width and (y + 1/2) / height.
    double fx = st.x * width_ - 0.5, fy = st.y * height_ - 0.5;
    double x0f = std::floor(fx), y0f = std::floor(fy);
    double ax = fx - x0f, ay = fy - y0f;
    int x0 = static_cast<int>(x0f), y0 = static_cast<int>(y0f);  // -1 to width - 1, height - 1
    int x1 = x0 + 1, y1 = y0 + 1;
    if (x0 < 0) x0 += width_;
    if (x1 >= width_) x1 -= width_;
    y0 = std::clamp(y0, 0, height_ - 1);
    y1 = std::clamp(y1, 0, height_ - 1);
    Vec3 top = texel(x0, y0) * (1 - ax) + texel(x1, y0) * ax;
    Vec3 bottom = texel(x0, y1) * (1 - ax) + texel(x1, y1) * ax;
    return finiteRadiance((top * (1 - ay) + bottom * ay) * scale_);
}

double EnvironmentMap::pdf(const Vec3& dir) const { return pdfAt(imageCoordinates(dir)); }

double EnvironmentMap::pdfAt(Point2 st) const {
    // Constant over each texel's cell: its probability over its solid angle, 2 pi / w x band.
    size_t row = std::min(static_cast<size_t>(st.y * height_), static_cast<size_t>(height_ - 1));
    return distribution_.density(st) / (2 * kPi * height_ * bands_[row]);
}

std::optional<EnvironmentMap::Sample> EnvironmentMap::sample(Point2 u) const {
    double density = 0;
    size_t column = 0, row = 0;
    Point2 st = distribution_.sample(u, &density, &column, &row);
    if (!(density > 0)) return std::nullopt;
    // Uniform over the cell's solid angle: phi uniform across the column, cos(theta) uniform
    // across the row's band, measured from the nearer pole so that 1 -+ cos(theta) keep their
    // precision there.
    const int y = static_cast<int>(row);
    const double f = std::clamp(st.y * height_ - y, 0.0, 1.0), band = bands_[row];
    double oneMinusCos, onePlusCos;
    if (2 * y < height_) {
        oneMinusCos = capArea(y, height_) + f * band;
        onePlusCos = 2 - oneMinusCos;
    } else {
        onePlusCos = capArea(height_ - 1 - y, height_) + (1 - f) * band;
        oneMinusCos = 2 - onePlusCos;
    }
    double cosTheta = 2 * y < height_ ? 1 - oneMinusCos : onePlusCos - 1;
    double sinTheta = std::sqrt(std::max(0.0, oneMinusCos * onePlusCos));
    double phi = 2 * kPi * (st.x - rotationTurns_) - kPi;
    Vec3 wi(sinTheta * std::cos(phi), cosTheta, sinTheta * std::sin(phi));
    // The density and radiance recomputed from wi, so that they agree with pdf() and eval()
    // to the bit, even where rounding moves wi across a texel's edge.
    const Point2 st2 = imageCoordinates(wi);
    double p = pdfAt(st2);
    if (!(p > 0)) return std::nullopt;
    return Sample{wi, evalAt(st2), p};
}

double EnvironmentMap::power(double sceneRadius) const {
    return kPi * sceneRadius * sceneRadius * 4 * kPi * luminance(averageRadiance());
}

}  // namespace glint
