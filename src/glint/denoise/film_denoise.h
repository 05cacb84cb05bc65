#pragma once
/// The denoiser (denoise.h) applied to a rendered film and its render passes (render/film/film.h):
/// what `glint --denoise`, `glint denoise` and the web page's preview call.

#include "glint/core/parallel.h"
#include "glint/render/film/film.h"

namespace glint {

/// `film` denoised, guided by `aovs` (the film's size; any pass left empty is not used; the
/// variance, when empty, is estimated from the image). Throws RenderError if the passes are
/// another size.
Film denoiseFilm(const Film& film, const RenderPasses& aovs, ThreadPool& pool);

/// Rows a band of denoiseFilmRows() reads on either side: more than the denoiser reaches from
/// a pixel (its passes' windows and patches, the variance's smoothing, the depth's gradient:
/// 14 rows).
constexpr int kDenoiseBandMargin = 24;

/// Rows [y0, y1) of denoiseFilm(film, aovs, pool), as a film of the image's width and y1 - y0
/// rows, computed from those rows and kDenoiseBandMargin more on either side: the same pixels
/// as the whole image's, so that a large image can be denoised a band at a time (the web page,
/// between which it hears Cancel).
Film denoiseFilmRows(const Film& film, const RenderPasses& aovs, int y0, int y1, ThreadPool& pool);

}  // namespace glint
