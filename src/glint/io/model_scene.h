#pragma once
/// A whole scene for a bare model file (`glint model.obj`, `glint model.gltf`): the model, and
/// what it lacks of a camera, lights and surroundings, chosen from its size (docs/cli.md,
/// "Rendering a model").

#include <memory>
#include <string>
#include <vector>

#include "glint/core/error.h"
#include "glint/io/gltf/gltf_loader.h"
#include "glint/core/input_file.h"
#include "glint/scene/scene.h"

namespace glint {

/// Whether `path` names a model rather than a scene file: its extension is .obj, .gltf or .glb
/// (any case).
bool isModelFile(const std::string& path);

struct ModelScene {
    std::unique_ptr<Scene> scene;
    /// What was assumed, for the user, as a sentence after "glint: " ("knot.obj has no camera
    /// or lights: framing it with ..."); empty when the model brought everything.
    std::string note;
};

/// What frameModel() adds.
struct Framing {
    bool camera = true;  ///< A camera, a floor and a sky.
    bool lights = true;  ///< A key and a fill light.
};

/// Adds to `scene`, which holds a model's geometry, what a bare model lacks (see
/// loadModelScene), for an image of the scene's size: by default camera, lights, floor and
/// background. Returns what it assumed, for the user. Throws SceneError if the scene has no
/// geometry.
std::string frameModel(Scene& scene, const std::string& name, Framing framing = {});

/// Loads the model at `path` and frames it for a `width` x `height` image (0 x 0: 640 x 480, or
/// 640 wide at the aspect ratio of a glTF file's camera). OBJ files have materials (MTL) but
/// no camera or lights; glTF files may have both, and what they have is used. What is missing
/// is added: a camera on the +z/+y diagonal (elevation about 27 degrees) whose 40-degree
/// vertical field of view holds the model's bounding sphere with a margin, with a grey ground
/// plane just under the model and a sky gradient; a key and a fill directional light. Faces
/// without a material of the file's are light grey. Throws SceneError like loadObj/loadGltf.
ModelScene loadModelScene(const std::string& path, std::vector<Diagnostic>& warnings, int width = 0,
                          int height = 0, const LoadLimits& limits = {});

/// The scene loadModelScene() makes of a glTF model already read (`model.name` names it in the
/// note): the model placed, its camera and lights, and Glint's for what it lacks.
ModelScene gltfModelScene(const GltfModel& model, int width = 0, int height = 0);

}  // namespace glint
