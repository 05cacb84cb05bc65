// libFuzzer harness for the OBJ loader (io/obj/obj_loader.h) and placing meshes (scene/mesh.h).
//
// An input is an OBJ text, optionally followed by a line "#mtl" and an MTL text that serves
// every `mtllib` of the OBJ. No file is ever read (LoadLimits::readFiles is off). A SceneError
// is the expected answer to bad input; any other exception escapes and libFuzzer reports it.
// A mesh that loads is placed in a scene, framed as `glint model.obj` frames it and rendered
// small (meshes are capped so that each input stays fast); a pixel that is NaN or infinite
// aborts.

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>
#include <vector>

#include "fuzz_render.h"
#include "glint/core/error.h"
#include "glint/scene/model_framing.h"
#include "glint/io/obj/obj_loader.h"
#include "glint/render/renderer.h"

namespace {

constexpr int kSide = 8;                // images of 8 x 8 pixels
constexpr size_t kMaxTriangles = 4096;  // larger meshes are loaded but not rendered
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
    std::vector<glint::Diagnostic> warnings;
    glint::MeshData mesh;
    try {
        mesh = glint::parseObj(objText, "fuzz.obj", warnings, options);
    } catch (const glint::SceneError& e) {
        (void)e.diagnostic().format("error");  // formatting the message must not fail either
        return 0;
    }
    for (const glint::Diagnostic& w : warnings) (void)w.format("warning");
    if (mesh.triangles.size() > kMaxTriangles) return 0;

    glint::Scene scene;
    scene.width = kSide;
    scene.height = kSide;
    scene.maxDepth = 2;
    glint::Material grey;
    grey.diffuse = glint::Vec3(0.7);
    try {
        glint::addMesh(scene, mesh, glint::Transform(), scene.addMaterial(grey));
        glint::frameModel(scene, "fuzz.obj");
    } catch (const glint::SceneError&) {
        return 0;  // beyond the coordinate range, or nothing of non-zero area
    }
    scene.prepare();
    glint::fuzz::renderExpectingFinitePixels(scene, "glint_fuzz_obj");
    return 0;
}
