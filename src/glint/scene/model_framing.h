#pragma once
/// A whole scene of a bare model (`glint model.obj`, `glint model.gltf`): the model, and what
/// it lacks of a camera, lights and surroundings, chosen from its size (docs/cli.md, "Rendering
/// a model"). Knows no file format: it takes a Model (scene/model.h).

#include <memory>
#include <string>

#include "glint/scene/model.h"
#include "glint/scene/scene.h"

namespace glint {

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

/// Adds to `scene`, which holds a model's geometry, what a bare model lacks, for an image of
/// the scene's size: by default camera, lights, floor and background. Returns what it assumed,
/// for the user. Throws SceneError, naming `name`, if the scene has no geometry.
std::string frameModel(Scene& scene, const std::string& name, Framing framing = {});

/// The scene of `model` for a `width` x `height` image (0 x 0: 640 x 480, or 640 wide at the
/// aspect ratio of the model's camera): the model placed as it is, with its camera and lights,
/// and what it lacks added: a camera on the +z/+y diagonal (elevation about 27 degrees) whose
/// 40-degree vertical field of view holds the model's bounding sphere with a margin, with a
/// grey ground plane just under the model and a sky gradient; a key and a fill directional
/// light. Faces without a material of the model's are light grey. `model.name` names it in the
/// note. Throws SceneError if the model has no faces of non-zero area or a placement lies beyond
/// the coordinate range.
ModelScene frameModelScene(const Model& model, int width = 0, int height = 0);

}  // namespace glint
