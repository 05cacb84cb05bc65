#pragma once
/// The graphics state of a scene being loaded, and the scene it builds. Every loader drives a
/// SceneBuilder and keeps no graphics state of its own: the course's scene files
/// (io/course/), models placed by a scene or framed as one (scene/model.h). The state is the
/// course's (docs/scene-format.md): a transform stack whose top places what is added, the
/// current material, the attenuation of the point lights declared next, and the lens. Meshes
/// are placed when the scene is finished, so that a mesh placed several times is stored once.
///
/// The builder knows no file format and no place in a file: it reports a problem as a
/// BuildError or a return value, and the loader says where in its file the problem is.

#include <cstdint>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "glint/core/error.h"
#include "glint/math/mat4.h"
#include "glint/math/transform.h"
#include "glint/scene/mesh.h"
#include "glint/scene/scene.h"

namespace glint {

/// A problem with what a loader asked the builder to do (a singular transform, a shape beyond
/// the coordinate range). The message has no file position: the loader adds its own.
class BuildError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

class SceneBuilder {
  public:
    SceneBuilder() : scene_(std::make_unique<Scene>()) {}

    /// The scene being built. Its settings (size, depth, output, background, sampling, filter)
    /// are set on it directly.
    Scene& scene() { return *scene_; }
    /// Reserves room for this many primitives (a loader's count of its file).
    void reserve(size_t triangles, size_t spheres, size_t shapes) {
        scene_->primitives.reserve(triangles, spheres, shapes);
    }

    // ---- The transform stack ---------------------------------------------------------------

    /// Right-multiplies the current transform by `m`: the last command given acts first.
    void applyTransform(const Mat4& m) {
        stack_.back() = stack_.back() * m;
        transformValid_ = false;
    }
    void pushTransform() { stack_.push_back(stack_.back()); }
    /// The current transform as given (not checked).
    const Mat4& matrix() const { return stack_.back(); }
    /// Replaces the current transform.
    void setMatrix(const Mat4& m) {
        stack_.back() = m;
        transformValid_ = false;
    }
    /// Restores the transform pushed last. Returns false, and changes nothing, when nothing was
    /// pushed.
    bool popTransform();
    /// The current transform, baked (object space to world space). Throws BuildError if it is
    /// singular or not finite. The common case, already baked, stays inline: a mesh of `tri`
    /// lines asks for it millions of times.
    const Transform& transform() {
        if (transformValid_ && transform_) return *transform_;
        return bakeTransform();
    }

    // ---- Materials -------------------------------------------------------------------------

    const Material& material() const { return material_; }
    /// The current material, to change: what is added next takes the changed one.
    Material& editMaterial() {
        materialChanged_ = true;
        return material_;
    }
    /// Replaces the whole current material.
    void setMaterial(const Material& m) {
        material_ = m;
        materialChanged_ = true;
    }
    /// The id of the current material, added to the scene when it changed since last asked
    /// (Scene::addMaterial reuses the last material when it is equal).
    uint32_t materialId() {
        if (materialChanged_) {
            if (pbr_) attachPbr();
            materialId_ = scene_->addMaterial(material_), materialChanged_ = false;
        }
        return materialId_;
    }
    /// The physically based maps and metalness of what follows (the scene file's `metallic`
    /// and `texture SLOT file`), to change; made on first use. While there are any, the
    /// current material gets a PbrMaterial of them whose factors come from the flat material
    /// (attachPbr()).
    PbrMaterial& editPbr() {
        materialChanged_ = true;
        if (!pbr_) pbr_.emplace();
        return *pbr_;
    }
    /// Drops the physically based maps and metalness: the current material is flat again.
    void clearPbr() {
        materialChanged_ = true;
        pbr_.reset();
        material_.pbr = 0;
    }
    /// Adds `m`, a material other than the current one (a light's surface, a model's default),
    /// and returns its id. The current material is added again the next time it is asked for.
    uint32_t addMaterial(const Material& m) {
        materialChanged_ = true;
        return scene_->addMaterial(m);
    }

    // ---- Lights and camera -----------------------------------------------------------------

    /// The attenuation that point lights declared from now on take (constant, linear,
    /// quadratic); 1 0 0 (none) at first.
    const Vec3& attenuation() const { return attenuation_; }
    void setAttenuation(const Vec3& a) { attenuation_ = a; }
    /// Adds `light` as it is (world space).
    void addLight(const LightSpec& light) { scene_->lights.push_back(light); }
    /// Adds a point light at `position` (world space) with the current attenuation.
    void addPointLight(const Vec3& position, const Vec3& colour);
    /// Adds the quad light `quad` (world space) and its surface, which camera and reflected
    /// rays see: emission only, from the front.
    void addQuadLight(const LightSpec& quad);
    /// The thin lens (Camera::apertureRadius, focusDistance), applied to the camera when the
    /// scene is finished: it may be given before the camera.
    void setLens(double apertureRadius, double focusDistance) {
        apertureRadius_ = apertureRadius;
        focusDistance_ = focusDistance;
    }

    // ---- Geometry, with the current material -----------------------------------------------
    // Triangles and planes come in world space: their loader places them with transform() and
    // checks each corner or argument itself. Spheres and shapes are placed here, by the current
    // transform, and checked as a whole.

    /// Adds the triangle of world-space corners `p` (counter-clockwise seen from the front),
    /// with shading normals if `normals` is not null. Returns false for a triangle of zero
    /// area, which is skipped.
    bool addTriangle(const Vec3 (&p)[3], const Vec3* normals) {
        return scene_->primitives.addTriangle(p[0], p[1], p[2], normals, materialId());
    }
    /// Adds the sphere at `center` of `radius` (>= 0) under the current transform. Returns
    /// false for radius 0: nothing to see, nothing added. Throws BuildError if the placed sphere
    /// reaches beyond the coordinate range or is too thin to search.
    bool addSphere(const Vec3& center, double radius);
    /// Adds a box, cylinder, cone or disk, placed in object space by `objectFromCanonical` (see
    /// shapes.h), under the current transform. Throws BuildError if it is degenerate, beyond
    /// the coordinate range or too thin once placed.
    void addShape(ShapeKind kind, const Mat4& objectFromCanonical, double k);
    /// Adds `plane` (world space).
    void addPlane(const Plane& plane) { scene_->primitives.addPlane(plane, materialId()); }

    /// Places `mesh` by `worldFromObject`, its faces without a material of their own taking
    /// `defaultMaterial`, when the scene is finished (MeshPlacer); `mesh` must live until then.
    /// `where` and `what` prefix errors about this placement.
    /// With `motion` (first key `worldFromObject`) it moves over the shutter (MeshPlacer::add).
    void placeMesh(const MeshData& mesh, const Transform& worldFromObject, uint32_t defaultMaterial,
                   FileLoc where = {}, std::string what = {},
                   std::shared_ptr<const MotionPath> motion = nullptr) {
        placer_.add(mesh, worldFromObject, defaultMaterial, std::move(where), std::move(what),
                    std::move(motion));
    }

    /// Places the meshes, applies the lens to the camera and hands out the scene (not yet
    /// prepared: see Scene::prepare). Warns in `warnings`, if given, of mesh triangles that
    /// placing made degenerate. Throws SceneError if a placed mesh lies beyond the coordinate
    /// range. The builder is spent.
    std::unique_ptr<Scene> finish(std::vector<Diagnostic>* warnings = nullptr);

  private:
    const Transform& bakeTransform();

    std::unique_ptr<Scene> scene_;
    std::vector<Mat4> stack_{Mat4::identity()};
    std::optional<Transform> transform_;  ///< stack_.back() baked; empty if singular.
    bool transformValid_ = false;
    /// Sets material_.pbr to a PbrMaterial of pbr_'s maps and metalness with the flat
    /// material's colour, roughness, emission, transmission and index.
    void attachPbr();

    Material material_;
    std::optional<PbrMaterial> pbr_;
    bool materialChanged_ = true;
    uint32_t materialId_ = 0;
    Vec3 attenuation_{1, 0, 0};
    double apertureRadius_ = 0, focusDistance_ = 0;
    MeshPlacer placer_;
};

}  // namespace glint
