// libFuzzer harness for the OBJ loader (io/obj/obj_loader.h) and the scene `glint model.obj`
// makes of a mesh (scene/model_framing.h).
//
// An input is an OBJ text, optionally followed by a line "#mtl" and an MTL text that serves
// every `mtllib` of the OBJ. No file is ever read (LoadLimits::readFiles is off). A SceneError
// is the expected answer to bad input; any other exception escapes and libFuzzer reports it.
// A mesh that loads is placed in a scene, framed as `glint model.obj` frames it and rendered
// small (meshes are capped so that each input stays fast); a pixel that is NaN or infinite
// aborts.

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "fuzz_render.h"
#include "glint/io/obj/obj_loader.h"

namespace {

constexpr std::string_view kMtlMarker = "\n#mtl\n";

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    std::string_view input(reinterpret_cast<const char*>(data), size);
    std::string_view objText = input;
    std::string mtl;
    glint::ObjOptions options;
    options.limits.readFiles = false;
    if (size_t at = input.find(kMtlMarker); at != std::string_view::npos) {
        objText = input.substr(0, at + 1);
        mtl = std::string(input.substr(at + kMtlMarker.size()));
        options.mtlText = &mtl;
    }
    return glint::fuzz::loadAndRenderModel(
        objText, "glint_fuzz_obj",
        [&](std::string_view text, std::vector<glint::Diagnostic>& warnings) {
            return glint::singleMeshModel(glint::parseObj(text, "fuzz.obj", warnings, options));
        });
}
