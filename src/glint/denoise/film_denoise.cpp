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
    std::vector<Vec3> color(n);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) color[static_cast<size_t>(y) * w + x] = film.at(x, y);
    auto pass = [&](const auto& v) { return v.size() == n ? v.data() : nullptr; };
    DenoiseInput in;
    in.width = w;
    in.height = h;
    in.color = color.data();
    in.albedo = pass(aovs.albedo);
    in.normal = pass(aovs.normal);
    in.depth = pass(aovs.depth);
    in.variance = pass(aovs.variance);
    const std::vector<Vec3> out = denoise(in, {&pool, 0});
    Film result(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) result.at(x, y) = out[static_cast<size_t>(y) * w + x];
    return result;
}

}  // namespace glint
