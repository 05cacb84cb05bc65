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

}  // namespace glint
