// libFuzzer harness for the PLY reader (io/ply/ply_loader.h) and the scene `glint model.ply`
// makes of a mesh (scene/model_framing.h).
//
// An input is a PLY file, ASCII or binary of either byte order. Memory is limited to 64 MiB, so
// that a header that claims a huge mesh is refused from its counts. A SceneError is the expected
// answer to bad input; any other exception escapes and libFuzzer reports it. A mesh that loads is
// framed as `glint model.ply` frames it and rendered small (meshes are capped so that each input
// stays fast); a pixel that is NaN or infinite aborts.

#include <cstdint>
#include <string_view>
#include <vector>

#include "fuzz_render.h"
#include "glint/io/ply/ply_loader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    glint::PlyOptions options;
    options.limits.readFiles = false;
    options.limits.memoryBytes = size_t(64) << 20;
    return glint::fuzz::loadAndRenderModel(
        std::string_view(reinterpret_cast<const char*>(data), size), "glint_fuzz_ply",
        [&](std::string_view input, std::vector<glint::Diagnostic>& warnings) {
            return glint::singleMeshModel(glint::parsePly(input, "fuzz.ply", warnings, options));
        });
}
