// libFuzzer harness for the CSE167x scene format (docs/scene-format.md).
//
// Every input is parsed as a scene file, strictly or (inputs of odd length) leniently,
// skipping unknown commands. A SceneError is the expected answer to bad input;
// any other exception escapes and libFuzzer reports it. A scene that parses is rendered
// small (clamped below so that each input stays fast), and a pixel that is NaN or infinite
// aborts: whatever the scene, no NaN or Inf may reach the film (issue 4).

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string_view>
#include <vector>

#include "fuzz_render.h"
#include "glint/core/error.h"
#include "glint/io/course/course_loader.h"
#include "glint/render/renderer.h"

namespace {

constexpr int kMaxSide = 8;                // image at most 8 x 8 pixels
constexpr int kMaxDepth = 3;               // at most 3 mirror bounces
constexpr uint32_t kMaxPrimitives = 4096;  // larger scenes are parsed but not rendered

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    std::string_view text(reinterpret_cast<const char*>(data), size);
    std::vector<glint::Diagnostic> warnings;
    std::unique_ptr<glint::Scene> scene;
    try {
        glint::CourseOptions options;
        options.limits.readFiles = false;  // `mesh` and `texture` must not reach the disk
        options.lenient = size % 2 == 1;   // both modes: inputs of odd length are lenient
        scene = glint::parseCourseScene(text, "fuzz.test", warnings, options);
    } catch (const glint::SceneError& e) {
        (void)e.diagnostic().format("error");  // formatting the message must not fail either
        return 0;
    }
    for (const glint::Diagnostic& w : warnings) (void)w.format("warning");

    scene->width = std::min(scene->width, kMaxSide);
    scene->height = std::min(scene->height, kMaxSide);
    scene->maxDepth = std::min(scene->maxDepth, kMaxDepth);
    if (scene->primitives.size() > kMaxPrimitives) return 0;
    scene->prepare();

    glint::fuzz::renderExpectingFinitePixels(*scene, "glint_fuzz_course");
    return 0;
}
