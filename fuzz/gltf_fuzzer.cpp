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
// aborts. A file with animations is posed still, then rendered posed at 37% of its first
// animation (io/gltf/gltf_animations.cpp).

#include <cstdint>
#include <string_view>
#include <vector>

#include "fuzz_render.h"
#include "glint/io/gltf/gltf_loader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    glint::GltfOptions options;
    options.limits.readFiles = false;
    options.limits.memoryBytes = size_t(64) << 20;
    return glint::fuzz::loadAndRenderModel(
        std::string_view(reinterpret_cast<const char*>(data), size), "glint_fuzz_gltf",
        [&](std::string_view input, std::vector<glint::Diagnostic>& warnings) {
            glint::GltfDocument document(input, "fuzz.gltf", warnings, options);
            glint::Model still = document.pose({}, warnings);
            if (document.animations().empty()) return still;
            const glint::ModelAnimation& a = document.animations()[0];
            return document.pose({"", a.start + 0.37 * (a.end - a.start)}, warnings);
        });
}
