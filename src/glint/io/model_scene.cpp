#include "glint/io/model_scene.h"

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "glint/io/gltf/gltf_loader.h"
#include "glint/io/obj/obj_loader.h"

namespace glint {

bool isModelFile(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext == ".obj" || isGltfFile(path);
}

ModelScene loadModelScene(const std::string& path, std::vector<Diagnostic>& warnings, int width,
                          int height, const LoadLimits& limits) {
    // The model is freed once placed, before the scene's BVH is built.
    if (isGltfFile(path)) {
        GltfOptions options;
        options.limits = limits;
        return frameModelScene(loadGltf(path, warnings, options), width, height);
    }
    ObjOptions options;
    options.limits = limits;
    return frameModelScene(singleMeshModel(loadObj(path, warnings, options)), width, height);
}

}  // namespace glint
