#include "glint/io/image/image_diff.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
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

}  // namespace glint
