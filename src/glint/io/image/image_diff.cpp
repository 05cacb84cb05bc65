#include "glint/io/image/image_diff.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <stdexcept>

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

}  // namespace glint
