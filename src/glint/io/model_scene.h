#pragma once
/// A whole scene for a bare model file (`glint model.obj`): the model, and a camera, lights and
/// a floor chosen from its size, since the file has none (docs/cli.md, "Rendering a model").

#include <memory>
#include <string>
#include <vector>

#include "glint/core/error.h"
#include "glint/io/input_file.h"
#include "glint/scene/scene.h"

namespace glint {

/// Whether `path` names a model rather than a scene file: its extension is .obj (any case).
bool isModelFile(const std::string& path);

struct ModelScene {
    std::unique_ptr<Scene> scene;
    /// What was assumed, for the user: "a camera at ... looking at ...; ...".
    std::string assumptions;
};

/// Adds to `scene`, which holds a model's geometry, what a bare model lacks (see
/// loadModelScene): camera, lights, floor, background, for an image of the scene's size.
/// Returns what it assumed, for the user. Throws SceneError if the scene has no geometry.
std::string frameModel(Scene& scene, const std::string& name);

/// Loads the OBJ model at `path` (with its MTL materials; a light grey elsewhere) and frames
/// it for a `width` x `height` image: a camera on the +z/+y diagonal (elevation about 27
/// degrees) whose 40-degree vertical field of view holds the model's bounding sphere with a
/// margin, a key and a fill directional light, a grey ground plane just under the model and a
/// sky gradient. Throws SceneError like loadObj.
ModelScene loadModelScene(const std::string& path, std::vector<Diagnostic>& warnings,
                          int width = 640, int height = 480, const LoadLimits& limits = {});

}  // namespace glint
