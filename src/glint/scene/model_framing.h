#pragma once
/// A whole scene of a bare model (`glint model.obj`, `glint model.gltf`): the model, and what
/// it lacks of a camera, lights and surroundings, chosen from its size (docs/cli.md, "Rendering
/// a model"). Knows no file format: it takes a Model (scene/model.h).
///
/// Two looks:
/// - the **studio** look (the default): the path tracer at kStudioSpp samples per pixel, the
///   studio environment (scene/studio_environment.h) plus the file's own lights, a shadow
///   catcher under the model, and the Khronos PBR Neutral tone mapper with the sRGB curve:
///   what a glTF viewer shows;
/// - the **classic** look, for the course's Whitted integrator: a key and a fill directional
///   light, a grey floor and a sky gradient, the course's conversion, one sample per pixel.

#include <memory>
#include <optional>
#include <string>

#include "glint/scene/environment.h"
#include "glint/scene/model.h"
#include "glint/scene/scene.h"

namespace glint {

struct ModelScene {
    std::unique_ptr<Scene> scene;
    bool framed = false;  ///< A model framed as a scene (false: a scene file's scene).
    /// What was assumed, for the user, as a sentence after "glint: " ("knot.obj has no camera
    /// or lights: framing it with ..."); empty when the model brought everything.
    std::string note;
    /// The model file's format extensions (Model::extensions): `glint --check` lists them.
    std::vector<FormatExtension> extensions;
    /// The model file's animations (Model::animations): `glint --check` lists them.
    std::vector<ModelAnimation> animations;
    /// The model file's material variants (Model::variants): the web page offers them.
    std::vector<std::string> variants;
    /// The index of the animation played (Model::animation); none when none was.
    std::optional<size_t> animation;
};

/// Camera rays per pixel of the studio look: enough for rough metal and soft shadows to come
/// out clean at 640 x 480 (docs/performance.md, "The model mode").
inline constexpr int kStudioSpp = 64;
/// Path length of the studio look, and its limits by kind: glass gets as deep as Cycles lets
/// it (12 bounces in all and through transmission), reflections as deep as before
/// (docs/performance.md, "Bounce limits").
inline constexpr int kStudioMaxDepth = 12;
inline constexpr BounceLimits kStudioBounces{
    .diffuse = 8, .glossy = 8, .transmission = 12, .volume = 8};

/// A model whose own lights light it more than this many times as brightly as the studio
/// environment does is taken to give them in physical units (glTF's candela and lux), and the
/// studio look chooses an exposure for them (modelExposure).
inline constexpr double kPhysicalLightRatio = 4;

/// The exposure (EV, in half stops) at which `scene`'s own lights light the point `at` as
/// brightly as the studio environment would, when they outshine it more than
/// kPhysicalLightRatio times (glTF files in physical units); 0 otherwise. `size` is the
/// model's radius: lights nearer the point than a quarter of it count from there.
double modelExposure(const Scene& scene, const Vec3& at, double size);

/// What a framed model stands on.
enum class ModelGround {
    Shadow,  ///< A shadow catcher: the environment, darkened by the model's shadow.
    Floor,   ///< An infinite light grey matte floor.
    None,    ///< Nothing: the model floats in its environment.
};

/// "shadow", "floor", "none".
const char* modelGroundName(ModelGround g);

/// How a bare model is shown.
struct ModelLook {
    bool studio = true;  ///< The studio look; false: the classic one (see the file comment).
    /// What rays that miss the model see, and (for the path tracer) what lights it: when unset,
    /// the look's own (the studio environment, or the classic sky); else this map, or black
    /// when it holds null.
    std::optional<std::shared_ptr<const EnvironmentMap>> environment;
    /// What the model stands on; unset: the look's own (a shadow, or the classic floor).
    std::optional<ModelGround> ground;

    /// The classic look (what `glint model.obj` rendered before the studio).
    static ModelLook classic() {
        ModelLook look;
        look.studio = false;
        return look;
    }
    ModelGround groundOrDefault() const {
        return ground.value_or(studio ? ModelGround::Shadow : ModelGround::Floor);
    }
};

/// What frameModel() adds.
struct Framing {
    bool camera = true;  ///< A camera and a sky (and the floor, if `floor`).
    bool lights = true;  ///< A key and a fill light.
    bool floor = true;   ///< With the camera: a grey floor under the model.
    /// Bounds to frame by in place of the scene's (Model::frameBounds).
    std::optional<Bounds3f> bounds;
};

/// Adds to `scene`, which holds a model's geometry, what a bare model lacks in the classic look,
/// for an image of the scene's size: by default camera, lights, floor and background. Returns
/// what it assumed, for the user. Throws SceneError, naming `name`, if the scene has no
/// geometry.
std::string frameModel(Scene& scene, const std::string& name, Framing framing = {});

/// The scene of `model` for a `width` x `height` image (0 x 0: 640 x 480, or 640 wide at the
/// aspect ratio of the model's camera), in `look`: the model placed as it is, with its camera
/// and lights, and what it lacks added. Glint's camera is on the +z/+y diagonal (elevation
/// about 27 degrees), its 40-degree vertical field of view holding the model's bounding sphere
/// with a margin; the ground lies just under the model's lowest point. Faces without a material
/// of the model's are light grey. The studio look sets the scene's integrator, samples, path
/// length and display (Scene::display); the classic look leaves the course's defaults.
/// `model.name` names it in the note. Throws SceneError if the model has no faces of non-zero
/// area or a placement lies beyond the coordinate range.
ModelScene frameModelScene(const Model& model, int width = 0, int height = 0,
                           const ModelLook& look = {});

}  // namespace glint
