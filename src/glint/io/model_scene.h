#pragma once
/// A whole scene for a bare model file (`glint model.obj`, `glint model.gltf`): the file read,
/// then framed (scene/model_framing.h).

#include <string>
#include <vector>

#include "glint/core/error.h"
#include "glint/core/input_file.h"
#include "glint/scene/model_framing.h"

namespace glint {

/// Whether `path` names a model rather than a scene file: its extension is .obj, .gltf or .glb
/// (any case).
bool isModelFile(const std::string& path);

/// Loads the model at `path` and frames it for a `width` x `height` image (frameModelScene).
/// Throws SceneError like loadObj/loadGltf.
ModelScene loadModelScene(const std::string& path, std::vector<Diagnostic>& warnings, int width = 0,
                          int height = 0, const LoadLimits& limits = {});

}  // namespace glint
