#include "glint/denoise/film_denoise.h"

#include <gtest/gtest.h>

#include "glint/math/rng.h"

namespace glint {
namespace {

// A noisy image with edges (two albedos, a step in depth), its passes, denoised whole and in
// bands of rows (as the web page does it, a band per call): every pixel the same, bit for bit.
TEST(DenoiseFilmRows, BandsAreTheWholeImagesRows) {
    const int w = 37, h = 90;
    Film film(w, h);
    RenderPasses passes(w, h);
    Rng rng(5);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const bool left = x < 15 + y / 6;
            Vec3 albedo = left ? Vec3(0.8, 0.3, 0.2) : Vec3(0.2, 0.5, 0.9);
            const size_t i = passes.index(x, y);
            // The lower half's albedo is noisy (an alpha-blended surface), and says so: the
            // albedo's own filter runs there too.
            if (y >= h / 2) {
                albedo = albedo * (0.8 + 0.4 * rng.uniform());
                passes.albedoVariance[i] = Vec3(0.01);
            }
            film.at(x, y) = albedo * (0.5 + rng.uniform());
            passes.albedo[i] = albedo;
            passes.normal[i] = left ? Vec3(0, 0, 1) : Vec3(0, 1, 0);
            passes.depth[i] = left ? 2.0 : 3.5;
            passes.variance[i] = Vec3(0.02 + 0.01 * rng.uniform());
        }
    ThreadPool pool(2);
    const Film whole = denoiseFilm(film, passes, pool, {DenoiserKind::Nlm});
    int bands = 0;
    for (int y0 = 0; y0 < h; y0 += 16, ++bands) {
        const int y1 = std::min(h, y0 + 16);
        const Film band = denoiseFilmRows(film, passes, y0, y1, pool);
        ASSERT_EQ(band.width(), w);
        ASSERT_EQ(band.height(), y1 - y0);
        for (int y = y0; y < y1; ++y)
            for (int x = 0; x < w; ++x)
                ASSERT_EQ(band.at(x, y - y0), whole.at(x, y)) << x << ", " << y;
    }
    EXPECT_EQ(bands, 6);
    // The denoiser did something: the result is not the noisy image.
    EXPECT_FALSE(whole.at(3, 40) == film.at(3, 40));
}

}  // namespace
}  // namespace glint
