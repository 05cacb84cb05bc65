#pragma once
/// The scene's geometry as one indexed set of primitives that accelerators are built over.
///
/// Primitive ids run over triangles first, then spheres: id < triangleCount() is a triangle.
/// Each primitive carries a material id; triangles may carry per-vertex shading normals.

#include <array>
#include <cstdint>
#include <vector>

#include "glint/core/huge_pages.h"
#include "glint/geometry/sphere.h"
#include "glint/geometry/triangle.h"

namespace glint {

/// Shading data for the closest hit, computed in double once per shaded hit.
struct SurfaceInteraction {
    Vec3 p;   ///< World-space hit point.
    Vec3 n;   ///< Unit shading normal (interpolated for triangles with vertex normals).
    Vec3 ng;  ///< Unit geometric normal.
    uint32_t material = 0;
};

class Primitives {
  public:
    /// Adds a triangle with world-space vertices; `normals` (world space, unit or zero) may be
    /// null for a flat triangle. A triangle of zero area as stored is dropped (it could never
    /// be seen, and the float test cannot reject it reliably): returns false then.
    bool addTriangle(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3* normals,
                     uint32_t material);
    void addSphere(const Sphere& sphere, uint32_t material);
    /// Room for this many more triangles and spheres, so that adding them does not reallocate.
    void reserve(size_t triangles, size_t spheres);

    uint32_t size() const { return static_cast<uint32_t>(triangles_.size() + spheres_.size()); }
    uint32_t triangleCount() const { return static_cast<uint32_t>(triangles_.size()); }
    uint32_t sphereCount() const { return static_cast<uint32_t>(spheres_.size()); }

    Bounds3f bounds(uint32_t id) const {
        return id < triangleCount() ? triangles_[id].bounds()
                                    : spheres_[id - triangleCount()].bounds();
    }
    /// The stored (float) vertices A, B, C of triangle `id`, world space.
    std::array<Vec3f, 3> triangleVertices(uint32_t id) const {
        const Triangle& t = triangles_[id];
        return {t.v0, t.v1, t.v2};
    }
    /// Bounds of everything.
    Bounds3f bounds() const;

    /// Tests primitive `id` in float; if it is hit within the ray's range and closer than
    /// `hit` (closerHit), fills `hit` and returns true.
    bool intersect(uint32_t id, const TraversalRay& ray, Hit& hit) const {
        float t;
        bool found = id < triangleCount()
                         ? intersectTriangle(triangles_[id], ray, t)
                         : intersectSphere(sphereSearch_[id - triangleCount()], ray, t);
        if (!found || !closerHit(t, id, hit)) return false;
        hit = {t, id};
        return true;
    }
    const Triangle& triangle(uint32_t id) const { return triangles_[id]; }
    const SphereSearch& sphereSearch(uint32_t sphere) const { return sphereSearch_[sphere]; }

    /// Shading data for a hit that traversal returned for `ray`, refined in double.
    SurfaceInteraction interaction(const Ray& ray, const Hit& hit) const;

  private:
    static constexpr uint32_t kFlat = UINT32_MAX;

    // Large arrays in huge pages: scenes of millions of triangles fill them in one go.
    LargeVector<Triangle> triangles_;
    LargeVector<uint32_t> triangleMaterial_;
    /// Index into vertexNormals_, or kFlat; empty while no triangle has vertex normals.
    LargeVector<uint32_t> triangleNormals_;
    LargeVector<std::array<Vec3, 3>> vertexNormals_;
    LargeVector<Sphere> spheres_;
    LargeVector<SphereSearch> sphereSearch_;
    LargeVector<uint32_t> sphereMaterial_;
};

}  // namespace glint
