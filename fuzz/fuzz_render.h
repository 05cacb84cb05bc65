#pragma once
// What every harness does with a scene that loaded: render it on one thread and stop the run,
// naming the harness, at the first pixel that is not finite (docs/robustness.md).

#include <cstdio>
#include <cstdlib>

#include "glint/render/renderer.h"

namespace glint::fuzz {

inline void renderExpectingFinitePixels(const Scene& scene, const char* harness) {
    RenderOptions options;
    options.threads = 1;
    RenderResult result = render(scene, options);
    for (int y = 0; y < result.film.height(); ++y)
        for (int x = 0; x < result.film.width(); ++x) {
            const Vec3& c = result.film.at(x, y);
            if (!isFinite(c)) {
                std::fprintf(stderr, "%s: non-finite pixel (%d, %d) = (%g, %g, %g)\n", harness, x,
                             y, c.x, c.y, c.z);
                std::abort();
            }
        }
}

}  // namespace glint::fuzz
