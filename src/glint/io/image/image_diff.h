#pragma once
/// Image comparison: as the course's grader does it (count "hot" 8-bit pixels), for linear
/// float images from path tracers (means, block means and error against a reference), and by
/// a perceptual measure, SSIM, on what a display shows.

#include <vector>

#include "glint/render/film/film.h"

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

/// The structural similarity of two grey images, and where it is lowest.
struct SsimResult {
    double mean = 1;               ///< Mean SSIM over every window position (the paper's MSSIM).
    double lowest = 1;             ///< The lowest SSIM of one window...
    int lowestX = 0, lowestY = 0;  ///< ...at this window centre (pixel; row 0 at the top).
    int windows = 0;               ///< Window positions averaged: (width - 10) x (height - 10).
};

/// SSIM (Wang, Bovik, Sheikh and Simoncelli, "Image quality assessment: from error visibility
/// to structural similarity", IEEE TIP 2004) of the grey images `x` and `y` (`width` x
/// `height`, row-major), with the paper's choices: at each position an 11 x 11
/// circular-symmetric Gaussian window of standard deviation 1.5 pixels, weights summing to 1,
/// gives the local means, standard deviations and covariance (its eqs. 14 to 16), and
///   SSIM = (2 mu_x mu_y + C1) (2 sigma_xy + C2) / ((mu_x^2 + mu_y^2 + C1)(sigma_x^2 +
///          sigma_y^2 + C2)),  C1 = (0.01 L)^2, C2 = (0.03 L)^2 (eq. 13),
/// L the values' dynamic range. The mean is over every position where the window lies inside
/// the image (eq. 17). 1 for equal images; symmetric in x and y; at most 1; negative where one
/// image's local contrast is the other's inverted. Throws std::invalid_argument when the sizes
/// differ from width x height or either side is below 11 pixels, or L is not positive.
SsimResult ssim(const std::vector<double>& x, const std::vector<double>& y, int width, int height,
                double dynamicRange = 1);

/// What SSIM compares a float image by: its display luma. Each channel is multiplied by
/// 2^`exposure`, clamped to [0, 1] and sRGB-encoded (as `imgdiff --preview` and `glint --srgb`
/// write it), then Y' = 0.2126 R' + 0.7152 G' + 0.0722 B', in [0, 1]. Row-major, row 0 at the
/// top; NaN channels count as 0.
std::vector<double> displayLuma(const Film& film, double exposure = 0);

/// A false-colour picture of the luminance difference of `a` against the `reference` (same
/// size), for looking at: red where `a` is brighter, blue where it is darker, black where they
/// agree; full intensity at |Y_a - Y_ref| = `scale` x the reference's mean luminance (linear
/// values in [0, 1], to be written without a transfer curve). Throws std::invalid_argument for
/// different sizes or a scale that is not positive.
Film differenceImage(const Film& a, const Film& reference, double scale);

}  // namespace glint
