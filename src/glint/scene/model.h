#pragma once
/// What a model file holds, whatever its format: meshes in their own space, where the file
/// places them, and the camera and lights it may have. The loaders in io/ make one of each file
/// (an OBJ file is one mesh placed once, as it is; a glTF file places its meshes by its nodes);
/// placeModel() puts a model in a scene being built, under a transform (the course's `mesh`
/// command), and model_framing.h makes a whole scene of one (`glint model.obj`).

#include <algorithm>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "glint/core/error.h"
#include "glint/math/bbox.h"
#include "glint/math/transform.h"
#include "glint/scene/camera.h"
#include "glint/scene/light_spec.h"
#include "glint/scene/mesh.h"
#include "glint/scene/scene_builder.h"

namespace glint {

/// One mesh of a model, placed once.
struct ModelPlacement {
    uint32_t mesh = 0;          ///< Index into Model::meshes.
    Transform worldFromObject;  ///< The model's space from the mesh's (a glTF node's transform).
    uint32_t node = 0;          ///< What placed it in the file (a glTF node), for messages.
    /// A placement that moves over the shutter: worldFromObject at evenly spaced times from
    /// the shutter's opening to its closing (the first is worldFromObject); empty when still.
    std::vector<Transform> motion{};
};

/// The camera a model file brings.
struct ModelCamera {
    CameraSpec spec;          ///< In the model's space.
    double aspectRatio = 0;   ///< Width / height the camera was made for; 0: not given.
    std::string description;  ///< "camera 0 'Main' (node 3)", for messages.
    bool own = true;          ///< The file's camera (false: one the command line placed).
};

/// A camera on a sphere around a target, as model-viewer's `camera-orbit` and the Khronos glTF
/// Render Fidelity scenarios place it (angles in degrees, +y up): theta is the azimuth about
/// +y from +z towards +x, phi the polar angle from +y; the eye is
/// target + radius (sin phi sin theta, cos phi, sin phi cos theta), looking at the target with
/// +y up and a vertical field of view of 45 degrees (their default).
struct OrbitCamera {
    double thetaDegrees = 0;
    double phiDegrees = 90;
    double radius = 1;
    Vec3 target;

    CameraSpec spec() const;
    /// "the orbit camera theta 30, phi 60, radius 4.75 around (0, 0, 0)", for messages.
    std::string describe() const;
};

/// Which camera to render a model file through (`glint --camera`). The loaders number a file's
/// cameras in the order they meet them (a glTF file: its camera nodes, depth first through the
/// default scene, children in order; numbered from 0).
struct CameraChoice {
    enum class Kind {
        First,  ///< The first camera Glint can use (a glTF file's first perspective camera).
        Index,  ///< Camera number `index`.
        Name,   ///< The first camera (or camera node) named `name`.
        None,   ///< None: the model is framed as if it had no camera.
        Orbit,  ///< None of the file's: `orbit` instead.
    };
    Kind kind = Kind::First;
    size_t index = 0;
    std::string name;
    OrbitCamera orbit;

    /// "none" is None, a decimal number an Index, "orbit:THETA,PHI,RADIUS[,TX,TY,TZ]" an Orbit
    /// (throws std::invalid_argument, saying why, for a malformed one: numbers not finite,
    /// radius not positive, phi not strictly between 0 and 180), anything else a Name; empty is
    /// First.
    static CameraChoice parse(const std::string& text);
    /// "camera 2", "camera 'Side'": for messages.
    std::string describe() const;
};

/// When a model is posed: which of its file's animations, at what time.
struct ModelTime {
    /// The animation: its index (a decimal number) or its name; empty for the first.
    std::string animation;
    /// Seconds into the animation; none: no animation is played (the nodes' own transforms).
    std::optional<double> seconds;
    /// The shutter, in seconds from `seconds`: open <= close; equal, no motion blur.
    double shutterOpen = 0, shutterClose = 0;
    /// Keys of what moves, evenly spaced over the shutter: between them transforms are
    /// interpolated (math/motion.h).
    int shutterKeys = 5;

    bool playing() const { return seconds.has_value(); }
    bool blurs() const { return shutterClose > shutterOpen; }
    /// The time of shutter key k (0 to shutterKeys - 1).
    double keyTime(int k) const {
        return seconds.value_or(0) + shutterOpen +
               (shutterClose - shutterOpen) * k / std::max(shutterKeys - 1, 1);
    }
};

/// One of a model file's animations, as listed for the user.
struct ModelAnimation {
    std::string name;
    double start = 0, end = 0;  ///< Seconds: the first and last key of any of its samplers.
    size_t channels = 0;
};

/// An extension of its format that a model file uses (glTF's KHR_materials_clearcoat, ...).
struct FormatExtension {
    std::string name;
    /// What Glint does with it, for the user: "rendered", "partly: ...", "ignored: ...".
    std::string support;
};

/// A model in its own space (Glint's conventions: right-handed, +y up).
struct Model {
    std::string name;  ///< The file it came from.
    /// Indexed like the file's meshes (then, for glTF, the copies of meshes posed by skins).
    /// A mesh no placement uses may be left empty.
    std::vector<MeshData> meshes;
    std::vector<ModelPlacement> placements;
    std::optional<ModelCamera> camera;
    /// A camera that moves over the shutter: its specs at the shutter's keys; empty if still.
    std::vector<CameraSpec> cameraMotion;
    /// In the model's space, physically: point and spot lights' colour their radiant
    /// intensity (glTF's candela), directional lights' their irradiance (lux), as the path
    /// tracer takes them.
    std::vector<LightSpec> lights;
    /// The format's extensions the file uses, by name (glTF's; none for other formats).
    std::vector<FormatExtension> extensions;
    /// The file's animations (glTF's), played or not.
    std::vector<ModelAnimation> animations;
    /// The names of the file's material variants (glTF's KHR_materials_variants), in order.
    std::vector<std::string> variants;
    /// What was played: "animation 0 'Walk' at 1.25 s"; empty when none was.
    std::string posed;
    std::optional<size_t> animation;  ///< The index of the animation played.
    /// Bounds to frame the model by (frameModelScene) in place of its own: those of the whole
    /// animation played, so that every frame of a sequence is framed alike.
    std::optional<Bounds3f> frameBounds;

    size_t triangles() const;  ///< Triangles placed by all placements together.
    /// The bounds of the vertices of every placed mesh, placed; empty for none.
    Bounds3f bounds() const;
};

/// The model of one mesh placed once, as it is (an OBJ file); it takes the mesh's name.
Model singleMeshModel(MeshData mesh);

/// Hands every placement of `model` to `builder` under `worldFromModel` (the scene's transform
/// of the whole model): a mesh placed several times is then stored once and instanced.
/// Triangles without a material of the model's take `defaultMaterial`; `where` and `what` prefix
/// errors about the placements (MeshPlacer::add). The model's camera and lights are not used.
/// Throws SceneError, naming the model's file, if a composed transform is singular. `model`
/// must live until the builder has finished. With `modelMotion` (keys of worldFromModel over
/// the shutter, the first worldFromModel), the whole model moves too.
void placeModel(SceneBuilder& builder, const Model& model, const Transform& worldFromModel,
                uint32_t defaultMaterial, const FileLoc& where = {}, const std::string& what = {},
                const std::vector<Transform>* modelMotion = nullptr);

}  // namespace glint
