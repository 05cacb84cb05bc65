#pragma once
// What every harness does with a scene that loaded: render it on one thread and stop the run,
// naming the harness, at the first pixel that is not finite (docs/robustness.md); and what the
// model readers' harnesses share, from the parse to that render.

#include <cstdio>
#include <cstdlib>
#include <string_view>
#include <vector>

#include "glint/core/error.h"
#include "glint/render/renderer.h"
#include "glint/scene/model_framing.h"

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

/// One input of a model reader's harness: `parse(input, warnings)` returns a Model or throws
/// SceneError, the expected answer to bad input (its message is formatted: that must not fail
/// either). A model of at most 4096 triangles becomes the scene `glint model.EXT` makes (its
/// cameras and lights, or Glint's framing) at 8 x 8 pixels and is rendered; larger ones are
/// loaded but not rendered, so that every input stays fast.
template <typename Parse>
int loadAndRenderModel(std::string_view input, const char* harness, Parse parse) {
    constexpr int kSide = 8;
    constexpr size_t kMaxTriangles = 4096;
    std::vector<Diagnostic> warnings;
    Model model;
    try {
        model = parse(input, warnings);
    } catch (const SceneError& e) {
        (void)e.diagnostic().format("error");
        return 0;
    }
    for (const Diagnostic& w : warnings) (void)w.format("warning");
    if (model.triangles() > kMaxTriangles) return 0;

    ModelScene m;
    try {
        m = frameModelScene(model, kSide, kSide);
    } catch (const SceneError&) {
        return 0;  // beyond the coordinate range, or nothing of non-zero area
    }
    Scene& scene = *m.scene;
    scene.maxDepth = 2;
    scene.prepare();
    renderExpectingFinitePixels(scene, harness);
    return 0;
}

}  // namespace glint::fuzz
