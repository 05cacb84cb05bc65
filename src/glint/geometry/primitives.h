#pragma once
/// The scene's geometry as one indexed set of primitives that accelerators are built over.
///
/// Primitive ids run over triangles first, then spheres, then the other bounded shapes (boxes,
/// cylinders, cones, disks), then instances, then planes: id < triangleCount() is a triangle,
/// and ids below boundedCount() have finite bounds (planes do not: accelerators test them
/// beside their tree). Each primitive carries a material id; triangles may carry per-vertex
/// shading normals and texture coordinates, stored only for scenes that have them.
///
/// An instance places a shared mesh: another Primitives object of triangles in the mesh's own
/// space, stored once however many instances place it (two-level acceleration: the scene's
/// BVH holds the instances, each shared mesh has a BVH of its own). A hit on an instance
/// carries the mesh's triangle in Hit::subId.

#include <algorithm>
#include <array>
#include <cstdint>
#include <iosfwd>
#include <memory>
#include <vector>

#include "glint/core/huge_pages.h"
#include "glint/geometry/deforming_mesh.h"
#include "glint/geometry/plane.h"
#include "glint/geometry/shapes.h"
#include "glint/geometry/sphere.h"
#include "glint/geometry/triangle.h"
#include "glint/math/motion.h"
#include "glint/math/transform.h"

namespace glint {

/// Texture coordinates (u, v) of a triangle corner.
using TexCoord = std::array<float, 2>;

/// Shading data for the closest hit, computed in double once per shaded hit.
struct SurfaceInteraction {
    Vec3 p;   ///< World-space hit point.
    Vec3 n;   ///< Unit shading normal (interpolated for triangles with vertex normals).
    Vec3 ng;  ///< Unit geometric normal.
    uint32_t material = 0;
    bool hasUv = false;  ///< Whether the primitive has texture coordinates: u and v are set.
    /// Texture coordinates interpolated at the hit, set only when `hasUv` (triangles with
    /// per-corner coordinates): left unset otherwise, so that the course's hits, which have
    /// none, pay nothing for them.
    double u = 0, v = 0;
    /// The second set of texture coordinates (glTF's TEXCOORD_1), set only when `hasUv1`.
    bool hasUv1 = false;
    double u1 = 0, v1 = 0;
    /// Interpolated vertex colour (RGB linear, and alpha), set only when `hasColor`.
    bool hasColor = false;
    Vec3 color{1};
    double colorAlpha = 1;
    /// Unit tangent (world space, along increasing u) and the bitangent's sign (B = sign
    /// n x t), from the file or generated; set only when `hasTangent`.
    bool hasTangent = false;
    Vec3 tangent;
    double tangentSign = 1;
    /// dp/du of the triangle (world space) from its first texture coordinates: the tangent
    /// direction for surfaces without tangents; zero when the coordinates are degenerate.
    Vec3 dpdu;
};
/// "SurfaceInteraction{p (x, y, z), n (..), ng (..), material 2, uv (u, v)}" (uv when it has one).
std::ostream& operator<<(std::ostream& out, const SurfaceInteraction& si);

/// A triangle's attributes beyond normals and first texture coordinates: glTF's second
/// texture coordinates, vertex colours and tangents (each present or absent as a whole).
struct TriangleExtras {
    static constexpr uint8_t kUv1 = 1, kColor = 2, kTangent = 4;
    uint8_t present = 0;  ///< Which of the three are set.
    std::array<TexCoord, 3> uv1{};
    std::array<std::array<float, 4>, 3> color{};    ///< Linear RGBA per corner.
    std::array<std::array<float, 4>, 3> tangent{};  ///< xyz world space, w the sign (+-1).
};

class Primitives {
  public:
    /// Adds a triangle with world-space vertices; `normals` (world space, interpolated at a hit
    /// and then normalised, so their lengths weigh them) may be null for a flat triangle, and `uvs`
    /// (texture coordinates of a, b, c) null for none. A triangle of zero area as stored is dropped
    /// (it could never be seen, and the float test cannot reject it reliably): returns false then.
    bool addTriangle(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3* normals,
                     uint32_t material) {
        if (!pushTriangle(a, b, c, material)) return false;
        if (normals || !triangleNormals_.empty()) addAttributes(normals, nullptr);
        return true;
    }
    bool addTriangle(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3* normals,
                     const TexCoord* uvs, uint32_t material) {
        if (!pushTriangle(a, b, c, material)) return false;
        if (normals || uvs || !triangleNormals_.empty()) addAttributes(normals, uvs);
        return true;
    }
    /// As above, with `extras` (may be null) for glTF's further attributes.
    bool addTriangle(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3* normals,
                     const TexCoord* uvs, const TriangleExtras* extras, uint32_t material) {
        if (!addTriangle(a, b, c, normals, uvs, material)) return false;
        if (extras || !triangleExtras_.empty()) addExtras(extras);
        return true;
    }
    void addSphere(const Sphere& sphere, uint32_t material);
    /// Adds a box, cylinder, cone or disk.
    void addShape(const Shape& shape, uint32_t material);
    void addPlane(const Plane& plane, uint32_t material);
    /// Registers a shared mesh for instances to place: triangles only, in the mesh's own
    /// space. `mesh` must stay where it is, unchanged, while this object lives. Returns its
    /// index for addInstance().
    uint32_t addSharedMesh(const Primitives& mesh);
    /// Places shared mesh `mesh` (an index from addSharedMesh) by `worldFromObject`. Returns
    /// the instance's world-space bounds.
    const Bounds3f& addInstance(uint32_t mesh, const Transform& worldFromObject);
    /// Room for this many more triangles, spheres and other shapes, so that adding them does
    /// not reallocate.
    void reserve(size_t triangles, size_t spheres, size_t shapes = 0);
    /// Room for this many more triangles with vertex normals and with texture coordinates.
    void reserveAttributes(size_t normals, size_t uvs);

    uint32_t size() const { return boundedCount() + planeCount(); }
    /// Primitives with finite bounds: triangles, spheres, shapes and instances (ids 0 to
    /// this - 1).
    uint32_t boundedCount() const {
        return static_cast<uint32_t>(triangles_.size() + spheres_.size() + shapes_.size() +
                                     instances_.size());
    }
    uint32_t triangleCount() const { return static_cast<uint32_t>(triangles_.size()); }
    uint32_t sphereCount() const { return static_cast<uint32_t>(spheres_.size()); }
    /// Boxes, cylinders, cones and disks.
    uint32_t shapeCount() const { return static_cast<uint32_t>(shapes_.size()); }
    uint32_t shapeCount(ShapeKind kind) const;
    uint32_t planeCount() const { return static_cast<uint32_t>(planes_.size()); }
    uint32_t instanceCount() const { return static_cast<uint32_t>(instances_.size()); }
    uint32_t sharedMeshCount() const { return static_cast<uint32_t>(sharedMeshes_.size()); }
    const Primitives& sharedMesh(uint32_t mesh) const { return *sharedMeshes_[mesh]; }
    /// Whether `id` is an instance.
    bool isInstance(uint32_t id) const {
        return id < boundedCount() && id >= triangleCount() + sphereCount() + shapeCount();
    }
    /// Instance `id`'s shared mesh (an index for sharedMesh()) and placement (isInstance(id)).
    uint32_t instanceMesh(uint32_t id) const { return instance(id).search.mesh(); }
    const Transform& instanceTransform(uint32_t id) const { return instance(id).worldFromObject; }
    /// Triangles the instances place, each counted once per instance (stored once per mesh).
    size_t instancedTriangleCount() const;
    /// Triangles with per-corner texture coordinates.
    uint32_t texturedTriangleCount() const { return static_cast<uint32_t>(cornerUvs_.size()); }
    /// Whether primitive `id` has texture coordinates (only triangles can).
    bool hasTexCoords(uint32_t id) const {
        return id < triangleCount() && !triangleUvs_.empty() && triangleUvs_[id] != kFlat;
    }
    /// The material id of primitive `id` (< size()); kMixedMaterials for an instance, whose
    /// triangles have their own.
    uint32_t materialOf(uint32_t id) const;
    static constexpr uint32_t kMixedMaterials = UINT32_MAX;

    // Motion over the shutter (math/motion.h).

    /// Moves sphere, shape or instance `id` over the shutter along `path`, whose first key
    /// placed it (an instance's placement is that key): at shutter time u it lies where
    /// path.delta(u) takes it, and its bounds are those it sweeps. Triangles do not move:
    /// a moving mesh is an instance.
    void setMotion(uint32_t id, MotionPath path);
    bool hasMotion() const { return !motionKeys_.empty(); }
    /// The motion of primitive `id`; null when it does not move.
    const MotionPath* motion(uint32_t id) const {
        if (motionKeys_.empty()) [[likely]]
            return nullptr;
        if (id < triangleCount() || id >= boundedCount()) return nullptr;
        const uint64_t key = motionKey(id);
        auto it = std::lower_bound(motionKeys_.begin(), motionKeys_.end(), key);
        return it != motionKeys_.end() && *it == key ? &motions_[it - motionKeys_.begin()]
                                                     : nullptr;
    }

    /// Makes this mesh's triangles deform over the shutter: `d` holds every triangle (in the
    /// order added, triangles only) keyed over the shutter. Searches and shading then take
    /// them at the calling thread's shutter time; bounds() is the bounds they sweep. For shared
    /// meshes (the only ones that may deform): call it before addSharedMesh(). Their instances
    /// count as moving (by a still path unless setMotion gives another), so accelerators
    /// search them beside their trees, where deformation is searched.
    void setDeformation(std::shared_ptr<const DeformingMesh> d);
    /// The deformation of this mesh's triangles; null when they are still.
    const DeformingMesh* deformation() const { return deformation_.get(); }

    /// Bounds of bounded primitive `id` (< boundedCount()); swept over the shutter if it moves.
    Bounds3f bounds(uint32_t id) const {
        if (const MotionPath* m = motion(id)) [[unlikely]]
            return m->sweep(stillBounds(id));
        return stillBounds(id);
    }
    /// Bounds of bounded primitive `id` where it was added.
    Bounds3f stillBounds(uint32_t id) const {
        if (id < triangleCount()) return triangles_[id].bounds();
        id -= triangleCount();
        if (id < sphereCount()) return spheres_[id].bounds();
        id -= sphereCount();
        return id < shapeCount() ? shapes_[id].bounds() : instances_[id - shapeCount()].bounds;
    }
    /// The stored (float) vertices A, B, C of triangle `id`, world space.
    std::array<Vec3f, 3> triangleVertices(uint32_t id) const {
        const Triangle& t = triangles_[id];
        return {t.v0, t.v1, t.v2};
    }
    /// Bounds of every bounded primitive (planes excluded).
    Bounds3f bounds() const;

    /// Tests primitive `id` in float; if it is hit within the ray's range and closer than
    /// `hit` (closerHit), fills `hit` and returns true.
    bool intersect(uint32_t id, const TraversalRay& ray, Hit& hit) const {
        if (const MotionPath* m = motion(id)) [[unlikely]]
            return intersectMoving(id, *m, ray, hit);
        if (isInstance(id)) return intersectInstance(id, ray, hit);
        float t;
        bool found = id < triangleCount()  ? intersectTriangle(triangleNow(id), ray, t)
                     : id < boundedCount() ? intersectShape(shapeSearch(id), ray, t)
                                           : intersectPlane(planeSearch(id), ray, t);
        if (!found || !closerHit(t, id, hit)) return false;
        hit = {t, id};
        return true;
    }
    /// Triangle `id` as stored (as it is at the shutter's middle, if the mesh deforms).
    const Triangle& triangle(uint32_t id) const { return triangles_[id]; }
    /// Triangle `id` as searched and shaded: at the calling thread's shutter time if the mesh
    /// deforms.
    Triangle triangleNow(uint32_t id) const {
        if (deformation_) [[unlikely]]
            return deformation_->at(id, shutterTime());
        return triangles_[id];
    }
    /// Sphere `i` (0 to sphereCount() - 1; its primitive id is triangleCount() + i).
    const Sphere& sphere(uint32_t i) const { return spheres_[i]; }
    /// Box, cylinder, cone or disk `i` (0 to shapeCount() - 1; its primitive id is
    /// triangleCount() + sphereCount() + i).
    const Shape& shape(uint32_t i) const { return shapes_[i]; }
    /// Whether `id` is a sphere.
    bool isSphere(uint32_t id) const {
        return id >= triangleCount() && id - triangleCount() < sphereCount();
    }
    /// The float search record of sphere, shape or instance `id` (triangleCount() <= id <
    /// boundedCount()); an instance's maps the ray into its mesh's space and names the mesh.
    const ShapeSearch& shapeSearch(uint32_t id) const {
        id -= triangleCount();
        if (id < sphereCount()) return sphereSearch_[id];
        id -= sphereCount();
        return id < shapeCount() ? shapeSearch_[id] : instances_[id - shapeCount()].search;
    }
    /// The float search record of plane `id` (boundedCount() <= id < size()).
    const PlaneSearch& planeSearch(uint32_t id) const { return planeSearch_[id - boundedCount()]; }
    /// Plane `id` (boundedCount() <= id < size()).
    const Plane& plane(uint32_t id) const { return planes_[id - boundedCount()]; }

    /// The texture coordinates and extras (not the position or normals) of triangle `id`
    /// (< triangleCount()) at barycentrics (b1, b2) of its second and third vertices: what a
    /// light sampler needs to evaluate a textured emitter at a point it chose.
    SurfaceInteraction triangleAttributes(uint32_t id, double b1, double b2) const;
    /// Shading data for a hit that traversal returned for `ray`, refined in double.
    SurfaceInteraction interaction(const Ray& ray, const Hit& hit) const;

  private:
    static constexpr uint32_t kFlat = UINT32_MAX;
    /// In triangleNormals_: the triangle has texture coordinates but no vertex normals.
    static constexpr uint32_t kNoNormals = UINT32_MAX - 1;

    struct Instance {
        Transform worldFromObject;
        Bounds3f bounds;     ///< World space, padded like shapes' (paddedSearchBounds).
        ShapeSearch search;  ///< Kind Instance: objectFromWorld and the mesh index.
    };

    const Instance& instance(uint32_t id) const {
        return instances_[id - triangleCount() - sphereCount() - shapeCount()];
    }
    /// intersect() for a moving primitive: the ray mapped to where the primitive was added,
    /// at the calling thread's shutter time.
    [[gnu::noinline]] bool intersectMoving(uint32_t id, const MotionPath& m,
                                           const TraversalRay& ray, Hit& hit) const;
    /// interaction() of a primitive where it was added.
    SurfaceInteraction stillInteraction(const Ray& ray, const Hit& hit) const;
    /// intersect() for an instance: every triangle of its mesh, one at a time (a reference
    /// for accelerators, which search the mesh's BVH instead).
    [[gnu::noinline]] bool intersectInstance(uint32_t id, const TraversalRay& ray, Hit& hit) const;
    /// interaction() for boxes, cylinders, cones, disks, instances and planes.
    [[gnu::noinline]] SurfaceInteraction shapeInteraction(const Ray& ray, const Hit& hit) const;
    /// Stores the triangle unless it has zero area; returns whether it did.
    bool pushTriangle(const Vec3& a, const Vec3& b, const Vec3& c, uint32_t material);
    /// Records the newest triangle's normals and texture coordinates (either may be null).
    [[gnu::noinline]] void addAttributes(const Vec3* normals, const TexCoord* uvs);
    /// Records the newest triangle's extras (may be null).
    [[gnu::noinline]] void addExtras(const TriangleExtras* extras);
    /// Fills the extras of triangle `id` at barycentrics (b1, b2) into `si`.
    void extrasAt(uint32_t id, double b1, double b2, SurfaceInteraction& si) const;

    // Large arrays in huge pages: scenes of millions of triangles fill them in one go.
    LargeVector<Triangle> triangles_;
    LargeVector<uint32_t> triangleMaterial_;
    /// Index into vertexNormals_, or kFlat, or kNoNormals; empty while no triangle has vertex
    /// normals or texture coordinates (so flat, untextured scenes pay one test for both).
    LargeVector<uint32_t> triangleNormals_;
    LargeVector<std::array<Vec3, 3>> vertexNormals_;
    /// Index into cornerUvs_, or kFlat; empty while no triangle has texture coordinates.
    LargeVector<uint32_t> triangleUvs_;
    LargeVector<std::array<TexCoord, 3>> cornerUvs_;
    /// Index into extras_, or kFlat; empty while no triangle has extras.
    LargeVector<uint32_t> triangleExtras_;
    LargeVector<TriangleExtras> extras_;
    LargeVector<Sphere> spheres_;
    LargeVector<ShapeSearch> sphereSearch_;
    LargeVector<uint32_t> sphereMaterial_;
    LargeVector<Shape> shapes_;
    LargeVector<ShapeSearch> shapeSearch_;
    LargeVector<uint32_t> shapeMaterial_;
    std::vector<Instance> instances_;
    std::vector<const Primitives*> sharedMeshes_;
    std::vector<Bounds3f> sharedMeshBounds_;  ///< Object space.
    std::vector<Plane> planes_;               // few: a scene has a floor, perhaps a wall or two
    std::vector<PlaneSearch> planeSearch_;
    std::vector<uint32_t> planeMaterial_;
    /// Moving primitives by kind and index within their kind (ids shift as triangles, spheres
    /// and shapes are added; those do not), ascending; and their paths, in that order.
    std::vector<uint64_t> motionKeys_;
    std::vector<MotionPath> motions_;
    std::shared_ptr<const DeformingMesh> deformation_;
    uint64_t motionKey(uint32_t id) const {
        uint64_t kind = 0, index = id - triangleCount();
        if (index >= sphereCount()) index -= sphereCount(), kind = 1;
        if (kind == 1 && index >= shapeCount()) index -= shapeCount(), kind = 2;
        return kind << 32 | index;
    }
};

}  // namespace glint
