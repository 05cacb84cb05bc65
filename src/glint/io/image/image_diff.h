#pragma once
/// Image comparison: as the course's grader does it (count "hot" 8-bit pixels), and for linear
/// float images from path tracers (means, block means and error against a reference).

#include "glint/render/film.h"

namespace glint {

/// Number of pixels whose largest channel difference between RGB images `a` and `b` exceeds
/// `threshold` levels, skipping pixels where `mask` (grey, same size, may be null) is non-zero.
/// The images must have the same size and 3 channels.
long long countHotPixels(const Image8& a, const Image8& b, int threshold,
                         const Image8* mask = nullptr);

/// The largest channel difference over all unmasked pixels.
int maxChannelDifference(const Image8& a, const Image8& b, const Image8* mask = nullptr);

/// For lossy (JPEG) references: the images are averaged over `block` x `block` squares (which
/// hides chroma subsampling and ringing), and squares whose largest channel difference of the
/// averages exceeds `threshold` levels are counted. Sizes must be multiples of `block`.
long long countHotBlocks(const Image8& a, const Image8& b, int block, double threshold);

/// Mean absolute difference over all channels of all pixels, in levels.
double meanAbsDifference(const Image8& a, const Image8& b);

/// |a - b| / |b|, the difference relative to the reference value b: 0 when both are 0, +inf
/// when only b is 0, NaN when either is NaN.
double relativeDifference(double a, double b);

/// Where and how large the largest relative difference of block means is.
struct WorstBlock {
    double rel = 0;    ///< |mean_a - mean_b| / mean_b of the block.
    int x = 0, y = 0;  ///< The block's top-left pixel.
    int channel = -1;  ///< 0, 1, 2 for R, G, B; -1 for luminance.
};

/// A linear float image `a` (a render) compared with `b` (the reference), as `imgdiff --blocks`
/// reports it. Means are over all pixels; index 3 of the four-element arrays is luminance.
struct FilmComparison {
    int width = 0, height = 0, block = 0;
    int blocks = 0;  ///< Blocks compared: ceil(w / block) * ceil(h / block).
    double meanA[4] = {}, meanB[4] = {};
    double meanRel[4] = {};     ///< relativeDifference(meanA, meanB) per channel, luminance.
    WorstBlock worstLuminance;  ///< Of the blocks' mean luminance.
    WorstBlock worstChannel;    ///< Of the blocks' mean R, G and B: the largest of the three.
    double rmse[4] = {};        ///< sqrt(mean((a - b)^2)) over pixels, per channel, luminance.
};

/// Compares the float images `a` and `reference` (same size) in square blocks of `block`
/// pixels; blocks at the right and bottom edges are smaller when `block` does not divide the
/// size. A NaN anywhere makes the statistics it enters NaN. Throws std::invalid_argument for
/// different sizes or a block size below 1.
FilmComparison compareFilms(const Film& a, const Film& reference, int block);

}  // namespace glint
