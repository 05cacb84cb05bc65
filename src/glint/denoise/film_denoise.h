#pragma once
/// The denoiser (denoise.h) applied to a rendered film and its render passes (render/film/film.h):
/// what `glint --denoise`, `glint denoise` and the web page's preview call.

#include <string>
#include <string_view>

#include "glint/core/parallel.h"
#include "glint/denoise/network_denoise.h"
#include "glint/render/film/film.h"

namespace glint {

/// Which denoiser: the network (Open Image Denoise's U-Net and weights, network_denoise.h), the
/// non-local-means filter (denoise.h), or Auto: the network where its weights are here (a build
/// without them: the filter).
enum class DenoiserKind { Auto, Oidn, Nlm };

/// "auto", "oidn", "nlm"; and back (throws std::invalid_argument for another name).
std::string_view denoiserName(DenoiserKind kind);
DenoiserKind denoiserNamed(std::string_view name);
/// The denoiser Auto stands for: the network where the weights of `quality` for the passes
/// there are (`albedo`, `normal`) are here, else the filter.
DenoiserKind resolveDenoiser(DenoiserKind kind, DenoiseQuality quality = DenoiseQuality::Balanced,
                             bool albedo = true, bool normal = true);

struct FilmDenoiseOptions {
    DenoiserKind denoiser = DenoiserKind::Auto;
    DenoiseQuality quality = DenoiseQuality::Balanced;  ///< The network's.
};

/// What a denoiseFilm() did: "oidn balanced" or "nlm", and the pixels whose values were not
/// finite (NaN, infinity), taken as 0.
struct FilmDenoiseReport {
    std::string method;
    size_t nonFinite = 0;
};

/// `film` denoised, guided by `aovs` (the film's size; any pass left empty is not used; the
/// variance, when empty, is estimated from the image). Throws RenderError if the passes are
/// another size, std::runtime_error if the network's weights are not here.
Film denoiseFilm(const Film& film, const RenderPasses& aovs, ThreadPool& pool,
                 const FilmDenoiseOptions& options = {}, FilmDenoiseReport* report = nullptr);

/// Rows a band of denoiseFilmRows() reads on either side: more than the denoiser reaches from
/// a pixel (its passes' windows and patches, the variance's smoothing, the depth's gradient:
/// 14 rows).
constexpr int kDenoiseBandMargin = 24;

/// Rows [y0, y1) of denoiseFilm(film, aovs, pool) with the non-local-means filter, as a film of the
/// image's width and y1 - y0 rows, computed from those rows and kDenoiseBandMargin more on either
/// side: the same pixels as the whole image's, so that a large image can be denoised a band at a
/// time (the web page, between which it hears Cancel).
Film denoiseFilmRows(const Film& film, const RenderPasses& aovs, int y0, int y1, ThreadPool& pool);

}  // namespace glint
