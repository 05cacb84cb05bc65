#include "glint/render/image_diff.h"

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

}  // namespace glint
