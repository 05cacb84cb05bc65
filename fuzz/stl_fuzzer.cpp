// libFuzzer harness for the STL reader (io/stl/stl_loader.h) and the scene `glint model.stl`
// makes of a mesh (scene/model_framing.h).
//
// An input is an STL file, ASCII or binary. Memory is limited to 64 MiB, so that a header
// that claims a huge mesh is refused from its counts. A SceneError is the expected answer to bad
// input; any other exception escapes and libFuzzer reports it. A mesh that loads is framed as
// `glint model.stl` frames it and rendered small (meshes are capped so that each input stays
// fast); a pixel that is NaN or infinite aborts.

#include <cstdint>
#include <string_view>
#include <vector>

#include "fuzz_render.h"
#include "glint/io/stl/stl_loader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    glint::StlOptions options;
    options.limits.readFiles = false;
    options.limits.memoryBytes = size_t(64) << 20;
    return glint::fuzz::loadAndRenderModel(
        std::string_view(reinterpret_cast<const char*>(data), size), "glint_fuzz_stl",
        [&](std::string_view input, std::vector<glint::Diagnostic>& warnings) {
            return glint::singleMeshModel(glint::parseStl(input, "fuzz.stl", warnings, options));
        });
}
