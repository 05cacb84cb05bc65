#pragma once
/// Triangle meshes as a file describes them (io/obj/obj_loader.h reads OBJ), independent of where
/// they are placed, and how one is added to a scene under a transform. Loading and placing are
/// separate steps so that one mesh can be placed several times; MeshPlacer stores a mesh placed
/// several times once, as a shared mesh that instances place.

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "glint/core/error.h"
#include "glint/core/huge_pages.h"
#include "glint/math/motion.h"
#include "glint/math/transform.h"
#include "glint/scene/pbr_material.h"
#include "glint/scene/scene.h"

namespace glint {

/// A material a mesh file defines (an MTL entry), already in Glint's model.
struct MeshMaterial {
    std::string name;
    Material material;  ///< Its `texture` and `pbr` are 0: they are the two below.
    std::optional<Texture> texture;
    /// The physically based material the path tracer renders (glTF, OBJ's PBR extensions);
    /// `material` is its flat approximation for the Whitted integrator.
    std::optional<PbrMaterial> pbr;
    /// What fills the closed surfaces of this material (glTF's KHR_materials_volume_scatter):
    /// the path tracer's medium inside them (Material::interior); none: nothing scatters.
    std::optional<Medium> interior;
};

/// A triangle mesh in its own (object) space.
struct MeshData {
    static constexpr uint32_t kNone = UINT32_MAX;

    /// One corner of a triangle: indices into positions, normals, uvs, uv1s, colors and
    /// tangents (kNone: absent). A triangle has normals at all three corners or at none, and
    /// likewise each other attribute.
    struct Corner {
        uint32_t position = 0, normal = kNone, uv = kNone;
        uint32_t uv1 = kNone, color = kNone, tangent = kNone;
    };
    struct Triangle {
        std::array<Corner, 3> corners;  ///< Counter-clockwise seen from the front.
        uint32_t material = kNone;      ///< Index into `materials`; kNone: the placing default.
    };

    std::string name;                          ///< The file it came from, for messages.
    LargeVector<Vec3f> positions;              ///< Object space.
    LargeVector<Vec3f> normals;                ///< Object space, unit length or zero.
    LargeVector<TexCoord> uvs;                 ///< (u, v): u to the right, v up the image.
    LargeVector<TexCoord> uv1s;                ///< A second set (glTF's TEXCOORD_1), like uvs.
    LargeVector<std::array<float, 4>> colors;  ///< Linear RGBA vertex colours.
    /// Object-space unit tangents along increasing u, w the bitangent's sign: B = w (N x T).
    LargeVector<std::array<float, 4>> tangents;
    LargeVector<Triangle> triangles;  ///< Polygons are already split into triangles.
    std::vector<MeshMaterial> materials;
    size_t normalTriangles = 0;  ///< Triangles with vertex normals.
    size_t uvTriangles = 0;      ///< Triangles with texture coordinates.
    /// A mesh that deforms over the camera's shutter (a skin or morph targets, posed at each
    /// shutter key): `positions` and `normals` at evenly spaced times from the shutter's
    /// opening to its closing, each key the size of the array it keys (normalKeys may be empty);
    /// empty when the mesh is still. Placed, it becomes a DeformingMesh.
    std::vector<LargeVector<Vec3f>> positionKeys{}, normalKeys{};
};

/// What addMesh() did.
struct MeshPlacement {
    size_t added = 0;       ///< Triangles added.
    size_t degenerate = 0;  ///< Triangles skipped for zero area once placed.
};

/// Bytes that placing a mesh of this size takes beyond the scene's own estimate
/// (Scene::estimateBytes): the transformed vertices and normals, while it runs.
size_t meshPlacementBytes(size_t positions, size_t normals);

/// Adds `mesh`'s triangles to `scene`, placed by `worldFromObject`: positions as points,
/// normals by the inverse transpose (not renormalised, so that the interpolated normal is
/// the mapped one, as for an instance), texture coordinates as they are. Triangles without a mesh
/// material take `defaultMaterial` (an id in `scene`); the mesh's materials and textures are added
/// to the scene. Throws SceneError, naming the mesh file and the vertex, if a placed vertex lies
/// beyond the coordinate range (kMaxCoordinate).
MeshPlacement addMesh(Scene& scene, const MeshData& mesh, const Transform& worldFromObject,
                      uint32_t defaultMaterial);

/// Collects the placements of meshes while a scene loads and adds them all at its end. A mesh
/// placed once becomes world-space triangles (addMesh). A mesh placed more than once with the
/// same default material (or whose triangles all have their own) is stored once as a shared
/// mesh, in its own space, with a BVH of its own, and each placement adds an instance of it:
/// 100 copies of a model cost the memory of one.
class MeshPlacer {
  public:
    /// Records a placement of `mesh`, which must live until place() has run. `where` and
    /// `what` (e.g. "mesh 'bunny.obj'") prefix errors about this placement; `where` may be
    /// empty.
    /// With `motion` (whose first key is `worldFromObject`), the placement moves over the
    /// shutter: it becomes an instance that moves (Primitives::setMotion), even if alone. A
    /// deforming mesh (MeshData::positionKeys) is likewise always an instance.
    void add(const MeshData& mesh, const Transform& worldFromObject, uint32_t defaultMaterial,
             FileLoc where = {}, std::string what = {},
             std::shared_ptr<const MotionPath> motion = nullptr);
    size_t size() const { return placements_.size(); }

    /// Adds every recorded placement to `scene`, in the order recorded, and forgets them.
    /// Returns what each placement added (instances count their mesh's triangles), and warns
    /// once in `warnings` (if given) of triangles that placing made degenerate. Throws
    /// SceneError if a placed vertex would lie beyond the coordinate range.
    std::vector<MeshPlacement> place(Scene& scene, std::vector<Diagnostic>* warnings = nullptr);

  private:
    struct Placement {
        const MeshData* mesh;
        Transform worldFromObject;
        uint32_t defaultMaterial;
        FileLoc where;
        std::string what;
        std::shared_ptr<const MotionPath> motion;
    };
    std::vector<Placement> placements_;
};

}  // namespace glint
