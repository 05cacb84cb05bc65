#pragma once
/// The denoiser (denoise.h) applied to a rendered film and its render passes (render/film.h):
/// what `glint --denoise`, `glint denoise` and the web page's preview call.

#include "glint/core/parallel.h"
#include "glint/render/film.h"

namespace glint {

/// `film` denoised, guided by `aovs` (the film's size; any pass left empty is not used; the
/// variance, when empty, is estimated from the image). Throws RenderError if the passes are
/// another size.
Film denoiseFilm(const Film& film, const RenderPasses& aovs, ThreadPool& pool);

}  // namespace glint
