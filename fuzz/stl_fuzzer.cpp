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
#include "glint/core/error.h"
#include "glint/io/stl/stl_loader.h"
#include "glint/scene/model_framing.h"

namespace {

constexpr int kSide = 8;                // images of 8 x 8 pixels
constexpr size_t kMaxTriangles = 4096;  // larger meshes are loaded but not rendered

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    std::string_view input(reinterpret_cast<const char*>(data), size);
    glint::StlOptions options;
    options.limits.readFiles = false;
    options.limits.memoryBytes = size_t(64) << 20;
    std::vector<glint::Diagnostic> warnings;
    glint::MeshData mesh;
    try {
        mesh = glint::parseStl(input, "fuzz.stl", warnings, options);
    } catch (const glint::SceneError& e) {
        (void)e.diagnostic().format("error");  // formatting the message must not fail either
        return 0;
    }
    for (const glint::Diagnostic& w : warnings) (void)w.format("warning");
    if (mesh.triangles.size() > kMaxTriangles) return 0;

    glint::ModelScene m;
    try {
        m = glint::frameModelScene(glint::singleMeshModel(std::move(mesh)), kSide, kSide);
    } catch (const glint::SceneError&) {
        return 0;  // beyond the coordinate range, or nothing of non-zero area
    }
    glint::Scene& scene = *m.scene;
    scene.maxDepth = 2;
    scene.prepare();
    glint::fuzz::renderExpectingFinitePixels(scene, "glint_fuzz_stl");
    return 0;
}
