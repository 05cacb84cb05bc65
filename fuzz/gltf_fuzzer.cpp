// libFuzzer harness for the glTF loader (io/gltf/gltf_loader.h) and the scenes made of glTF models
// (scene/model_framing.h).
//
// An input is a glTF asset: JSON text, or a binary .glb (recognised by its magic). No file is
// ever read (LoadLimits::readFiles is off): only data: URI buffers and images and a .glb's own
// binary chunk are used. Memory is limited to 64 MiB, so that an embedded image whose header
// claims a huge size is refused before it is decoded. A SceneError is the expected answer to bad
// input; any other exception escapes and libFuzzer reports it. A model that loads becomes the
// scene `glint model.gltf` makes (its camera and lights, or Glint's framing) and is rendered
// small (models are capped so that each input stays fast); a pixel that is NaN or infinite
// aborts.

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string_view>
#include <vector>

#include "fuzz_render.h"
#include "glint/core/error.h"
#include "glint/io/gltf/gltf_loader.h"
#include "glint/scene/model_framing.h"
#include "glint/render/renderer.h"

namespace {

constexpr int kSide = 8;                // images of at most 8 x 8 pixels
constexpr size_t kMaxTriangles = 4096;  // larger models are loaded but not rendered

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    std::string_view input(reinterpret_cast<const char*>(data), size);
    glint::GltfOptions options;
    options.limits.readFiles = false;
    options.limits.memoryBytes = size_t(64) << 20;
    std::vector<glint::Diagnostic> warnings;
    glint::Model model;
    try {
        model = glint::parseGltf(input, "fuzz.gltf", warnings, options);
    } catch (const glint::SceneError& e) {
        (void)e.diagnostic().format("error");  // formatting the message must not fail either
        return 0;
    }
    for (const glint::Diagnostic& w : warnings) (void)w.format("warning");
    if (model.triangles() > kMaxTriangles) return 0;

    glint::ModelScene m;
    try {
        m = glint::frameModelScene(model, kSide, kSide);
    } catch (const glint::SceneError&) {
        return 0;  // beyond the coordinate range, or nothing of non-zero area
    }
    glint::Scene& scene = *m.scene;
    scene.maxDepth = 2;
    scene.prepare();
    glint::fuzz::renderExpectingFinitePixels(scene, "glint_fuzz_gltf");
    return 0;
}
