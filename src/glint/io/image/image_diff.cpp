#include "glint/io/image/image_diff.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <stdexcept>

#include "glint/render/film/display.h"

namespace glint {
namespace {

void checkComparable(const Image8& a, const Image8& b, const Image8* mask) {
    if (a.width != b.width || a.height != b.height || a.channels != 3 || b.channels != 3)
        throw std::invalid_argument("images differ in size or are not RGB");
    if (mask && (mask->width != a.width || mask->height != a.height))
        throw std::invalid_argument("mask differs in size from the images");
}

template <typename F>
void forEachUnmasked(const Image8& a, const Image8& b, const Image8* mask, F&& f) {
    checkComparable(a, b, mask);
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x) {
            if (mask && mask->at(x, y, 0) != 0) continue;
            int d = 0;
            for (int c = 0; c < 3; ++c) d = std::max(d, std::abs(a.at(x, y, c) - b.at(x, y, c)));
            f(d);
        }
}

}  // namespace

long long countHotPixels(const Image8& a, const Image8& b, int threshold, const Image8* mask) {
    long long hot = 0;
    forEachUnmasked(a, b, mask, [&](int d) { hot += d > threshold; });
    return hot;
}

int maxChannelDifference(const Image8& a, const Image8& b, const Image8* mask) {
    int worst = 0;
    forEachUnmasked(a, b, mask, [&](int d) { worst = std::max(worst, d); });
    return worst;
}

long long countHotBlocks(const Image8& a, const Image8& b, int block, double threshold) {
    checkComparable(a, b, nullptr);
    if (block < 1 || a.width % block || a.height % block)
        throw std::invalid_argument("image size is not a multiple of the block size");
    long long hot = 0;
    for (int by = 0; by < a.height; by += block)
        for (int bx = 0; bx < a.width; bx += block) {
            double worst = 0;
            for (int c = 0; c < 3; ++c) {
                long sum = 0;
                for (int y = by; y < by + block; ++y)
                    for (int x = bx; x < bx + block; ++x) sum += a.at(x, y, c) - b.at(x, y, c);
                worst = std::max(worst, std::abs(static_cast<double>(sum)) / (block * block));
            }
            hot += worst > threshold;
        }
    return hot;
}

double meanAbsDifference(const Image8& a, const Image8& b) {
    checkComparable(a, b, nullptr);
    double sum = 0;
    for (size_t i = 0; i < a.data.size(); ++i) sum += std::abs(a.data[i] - b.data[i]);
    return a.data.empty() ? 0 : sum / static_cast<double>(a.data.size());
}

double relativeDifference(double a, double b) {
    if (std::isnan(a) || std::isnan(b)) return std::numeric_limits<double>::quiet_NaN();
    if (a == b) return 0;  // 0 and 0, or the same infinity
    if (b == 0) return std::numeric_limits<double>::infinity();
    return std::abs(a - b) / std::abs(b);
}

namespace {

/// R, G, B and luminance of a pixel.
void channels(const Vec3& c, double out[4]) {
    out[0] = c.x;
    out[1] = c.y;
    out[2] = c.z;
    out[3] = luminance(c);
}

/// Keeps the larger of `w` and a block's relative difference `rel`; NaN wins, so that it shows.
void keepWorse(WorstBlock& w, double rel, int x, int y, int channel) {
    if (std::isnan(w.rel)) return;
    if (std::isnan(rel) || rel > w.rel) w = {rel, x, y, channel};
}

}  // namespace

FilmComparison compareFilms(const Film& a, const Film& reference, int block) {
    const Film& b = reference;
    if (a.width() != b.width() || a.height() != b.height())
        throw std::invalid_argument("images differ in size");
    if (block < 1) throw std::invalid_argument("block size must be at least 1");
    FilmComparison r;
    r.width = a.width();
    r.height = a.height();
    r.block = block;
    r.worstChannel.channel = 0;
    double sumA[4] = {}, sumB[4] = {}, sumSq[4] = {};
    for (int by = 0; by < r.height; by += block)
        for (int bx = 0; bx < r.width; bx += block) {
            double blockA[4] = {}, blockB[4] = {};
            for (int y = by; y < std::min(by + block, r.height); ++y)
                for (int x = bx; x < std::min(bx + block, r.width); ++x) {
                    double ca[4], cb[4];
                    channels(a.at(x, y), ca);
                    channels(b.at(x, y), cb);
                    for (int c = 0; c < 4; ++c) {
                        blockA[c] += ca[c];
                        blockB[c] += cb[c];
                        sumSq[c] += (ca[c] - cb[c]) * (ca[c] - cb[c]);
                    }
                }
            // Sums stand for means: the pixel counts of A and B are the same and cancel.
            for (int c = 0; c < 4; ++c) {
                sumA[c] += blockA[c];
                sumB[c] += blockB[c];
                double rel = relativeDifference(blockA[c], blockB[c]);
                keepWorse(c == 3 ? r.worstLuminance : r.worstChannel, rel, bx, by, c == 3 ? -1 : c);
            }
            ++r.blocks;
        }
    double pixels = static_cast<double>(r.width) * r.height;
    for (int c = 0; c < 4; ++c) {
        r.meanA[c] = pixels > 0 ? sumA[c] / pixels : 0;
        r.meanB[c] = pixels > 0 ? sumB[c] / pixels : 0;
        r.meanRel[c] = relativeDifference(r.meanA[c], r.meanB[c]);
        r.rmse[c] = pixels > 0 ? std::sqrt(sumSq[c] / pixels) : 0;
    }
    return r;
}

namespace {

constexpr int kSsimRadius = 5;  // the 11 x 11 window
constexpr double kSsimSigma = 1.5;

/// The window's separable weights: exp(-d^2 / (2 sigma^2)) for d = -5..5, normalised so that
/// the 2D window (their outer product) sums to 1.
std::array<double, 2 * kSsimRadius + 1> gaussianWeights() {
    std::array<double, 2 * kSsimRadius + 1> w{};
    double sum = 0;
    for (int d = -kSsimRadius; d <= kSsimRadius; ++d)
        sum += w[static_cast<size_t>(d + kSsimRadius)] =
            std::exp(-d * d / (2 * kSsimSigma * kSsimSigma));
    for (double& v : w) v /= sum;
    return w;
}

/// The weighted window sums of `v` at every position where the window fits ("valid"
/// filtering): (width - 10) x (height - 10) values, row-major.
std::vector<double> windowed(const std::vector<double>& v, int width, int height) {
    const auto w = gaussianWeights();
    const int ow = width - 2 * kSsimRadius, oh = height - 2 * kSsimRadius;
    std::vector<double> rows(static_cast<size_t>(ow) * height), out(static_cast<size_t>(ow) * oh);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < ow; ++x) {
            double s = 0;
            for (int k = 0; k <= 2 * kSsimRadius; ++k)
                s += w[static_cast<size_t>(k)] * v[static_cast<size_t>(y) * width + x + k];
            rows[static_cast<size_t>(y) * ow + x] = s;
        }
    for (int y = 0; y < oh; ++y)
        for (int x = 0; x < ow; ++x) {
            double s = 0;
            for (int k = 0; k <= 2 * kSsimRadius; ++k)
                s += w[static_cast<size_t>(k)] * rows[static_cast<size_t>(y + k) * ow + x];
            out[static_cast<size_t>(y) * ow + x] = s;
        }
    return out;
}

}  // namespace

SsimResult ssim(const std::vector<double>& x, const std::vector<double>& y, int width, int height,
                double dynamicRange) {
    const int side = 2 * kSsimRadius + 1;
    if (width < side || height < side)
        throw std::invalid_argument("SSIM needs images of at least 11 x 11 pixels");
    const size_t n = static_cast<size_t>(width) * static_cast<size_t>(height);
    if (x.size() != n || y.size() != n)
        throw std::invalid_argument("SSIM: the images are not width x height");
    if (!(dynamicRange > 0) || !std::isfinite(dynamicRange))
        throw std::invalid_argument("SSIM: the dynamic range must be positive");
    std::vector<double> xx(n), yy(n), xy(n);
    for (size_t i = 0; i < n; ++i) {
        xx[i] = x[i] * x[i];
        yy[i] = y[i] * y[i];
        xy[i] = x[i] * y[i];
    }
    const std::vector<double> mx = windowed(x, width, height), my = windowed(y, width, height),
                              mxx = windowed(xx, width, height), myy = windowed(yy, width, height),
                              mxy = windowed(xy, width, height);
    const double c1 = (0.01 * dynamicRange) * (0.01 * dynamicRange);
    const double c2 = (0.03 * dynamicRange) * (0.03 * dynamicRange);
    const int ow = width - 2 * kSsimRadius;
    SsimResult r;
    r.windows = static_cast<int>(mx.size());
    double sum = 0;
    for (size_t i = 0; i < mx.size(); ++i) {
        // Weighted variances and covariance about the window's means (eqs. 15, 16): E[v^2] -
        // mu^2. Round-off can make a variance slightly negative where the image is flat.
        const double vx = std::max(0.0, mxx[i] - mx[i] * mx[i]);
        const double vy = std::max(0.0, myy[i] - my[i] * my[i]);
        const double cxy = mxy[i] - mx[i] * my[i];
        const double s = (2 * mx[i] * my[i] + c1) * (2 * cxy + c2) /
                         ((mx[i] * mx[i] + my[i] * my[i] + c1) * (vx + vy + c2));
        sum += s;
        if (s < r.lowest || std::isnan(s)) {
            r.lowest = s;
            r.lowestX = static_cast<int>(i % static_cast<size_t>(ow)) + kSsimRadius;
            r.lowestY = static_cast<int>(i / static_cast<size_t>(ow)) + kSsimRadius;
        }
    }
    r.mean = sum / static_cast<double>(r.windows);
    return r;
}

std::vector<double> displayLuma(const Film& film, double exposure) {
    const double scale = std::exp2(exposure);
    std::vector<double> out(static_cast<size_t>(film.width()) * film.height());
    for (int y = 0; y < film.height(); ++y)
        for (int x = 0; x < film.width(); ++x) {
            const Vec3& c = film.at(x, y);
            out[static_cast<size_t>(y) * film.width() + x] = 0.2126 * srgbEncode(c.x * scale) +
                                                             0.7152 * srgbEncode(c.y * scale) +
                                                             0.0722 * srgbEncode(c.z * scale);
        }
    return out;
}

Film differenceImage(const Film& a, const Film& reference, double scale) {
    const Film& b = reference;
    if (a.width() != b.width() || a.height() != b.height())
        throw std::invalid_argument("images differ in size");
    if (!(scale > 0) || !std::isfinite(scale))
        throw std::invalid_argument("the difference scale must be positive");
    double mean = 0;
    for (int y = 0; y < b.height(); ++y)
        for (int x = 0; x < b.width(); ++x) mean += luminance(b.at(x, y));
    mean /= std::max(1.0, static_cast<double>(b.width()) * b.height());
    Film out(a.width(), a.height());
    const double full = scale * (mean > 0 ? mean : 1);
    for (int y = 0; y < a.height(); ++y)
        for (int x = 0; x < a.width(); ++x) {
            double d = (luminance(a.at(x, y)) - luminance(b.at(x, y))) / full;
            if (std::isnan(d)) d = 0;
            d = std::clamp(d, -1.0, 1.0);
            out.at(x, y) = d > 0 ? Vec3(d, 0.15 * d, 0) : Vec3(0, 0.3 * -d, -d);
        }
    return out;
}

}  // namespace glint
