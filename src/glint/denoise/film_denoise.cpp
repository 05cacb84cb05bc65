#include "glint/denoise/film_denoise.h"

#include <vector>

#include "glint/core/error.h"
#include "glint/denoise/denoise.h"

namespace glint {

Film denoiseFilm(const Film& film, const RenderPasses& aovs, ThreadPool& pool) {
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
    return Film(w, h, denoise(in, {&pool, 0}));
}

}  // namespace glint
