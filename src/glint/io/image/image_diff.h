#pragma once
/// Image comparison as the course's grader does it: count "hot" pixels.

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

}  // namespace glint
