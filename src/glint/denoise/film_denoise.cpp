#include "glint/denoise/film_denoise.h"

#include <algorithm>
#include <cstddef>
#include <stdexcept>
#include <type_traits>
#include <vector>

#include "glint/core/error.h"
#include "glint/denoise/denoise.h"

namespace glint {

std::string_view denoiserName(DenoiserKind kind) {
    switch (kind) {
        case DenoiserKind::Auto:
            return "auto";
        case DenoiserKind::Oidn:
            return "oidn";
        case DenoiserKind::Nlm:
            return "nlm";
    }
    return "?";
}

DenoiserKind denoiserNamed(std::string_view name) {
    for (DenoiserKind k : {DenoiserKind::Auto, DenoiserKind::Oidn, DenoiserKind::Nlm})
        if (denoiserName(k) == name) return k;
    throw std::invalid_argument("no denoiser '" + std::string(name) + "' (auto, oidn, nlm)");
}

DenoiserKind resolveDenoiser(DenoiserKind kind, DenoiseQuality quality, bool albedo, bool normal) {
    if (kind != DenoiserKind::Auto) return kind;
    return networkWeightsHere(networkChoice(quality, albedo, albedo && normal)) ? DenoiserKind::Oidn
                                                                                : DenoiserKind::Nlm;
}

Film denoiseFilm(const Film& film, const RenderPasses& aovs, ThreadPool& pool,
                 const FilmDenoiseOptions& options, FilmDenoiseReport* report) {
    const int w = film.width(), h = film.height();
    const size_t n = static_cast<size_t>(w) * h;
    if (!aovs.empty() && (aovs.width != w || aovs.height != h))
        throw RenderError("the render passes are " + std::to_string(aovs.width) + "x" +
                          std::to_string(aovs.height) + ", not the image's " + std::to_string(w) +
                          "x" + std::to_string(h));
    auto pass = [&](const auto& v) { return v.size() == n ? v.data() : nullptr; };
    DenoiseInput in;
    in.width = w;
    in.height = h;
    in.color = film.pixels().data();
    in.albedo = pass(aovs.albedo);
    in.normal = pass(aovs.normal);
    in.depth = pass(aovs.depth);
    in.variance = pass(aovs.variance);
    in.albedoVariance = pass(aovs.albedoVariance);
    if (resolveDenoiser(options.denoiser, options.quality, in.albedo, in.normal) ==
        DenoiserKind::Oidn) {
        NetworkDenoised out = networkDenoise(in, options.quality, pool);
        if (report)
            *report = {"oidn " + std::string(denoiseQualityName(options.quality)), out.nonFinite};
        return Film(w, h, std::move(out.color));
    }
    if (report) *report = {"nlm", 0};
    return Film(w, h, denoise(in, {&pool, 0}));
}

Film denoiseFilmRows(const Film& film, const RenderPasses& aovs, int y0, int y1, ThreadPool& pool) {
    const int w = film.width(), h = film.height();
    y0 = std::clamp(y0, 0, h);
    y1 = std::clamp(y1, y0, h);
    const int a0 = std::max(0, y0 - kDenoiseBandMargin), a1 = std::min(h, y1 + kDenoiseBandMargin);
    // The band with its margins, film and passes alike.
    const size_t first = static_cast<size_t>(a0) * w, count = static_cast<size_t>(a1 - a0) * w;
    auto rows = [&](const auto& v) {
        using V = std::decay_t<decltype(v)>;
        if (v.empty()) return V();
        return V(v.begin() + static_cast<std::ptrdiff_t>(first),
                 v.begin() + static_cast<std::ptrdiff_t>(first + count));
    };
    Film band(w, a1 - a0);
    for (int y = a0; y < a1; ++y)
        for (int x = 0; x < w; ++x) band.at(x, y - a0) = film.at(x, y);
    RenderPasses bandPasses;
    if (!aovs.empty()) {
        if (aovs.width != w || aovs.height != h)
            throw RenderError("the render passes are not the image's size");
        bandPasses.width = w;
        bandPasses.height = a1 - a0;
        bandPasses.albedo = rows(aovs.albedo);
        bandPasses.normal = rows(aovs.normal);
        bandPasses.variance = rows(aovs.variance);
        bandPasses.albedoVariance = rows(aovs.albedoVariance);
        bandPasses.depth = rows(aovs.depth);
    }
    const Film denoised = denoiseFilm(band, bandPasses, pool, {DenoiserKind::Nlm});
    Film out(w, y1 - y0);
    for (int y = y0; y < y1; ++y)
        for (int x = 0; x < w; ++x) out.at(x, y - y0) = denoised.at(x, y - a0);
    return out;
}

}  // namespace glint
