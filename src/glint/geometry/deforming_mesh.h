#pragma once
/// Triangles whose vertices move over the camera's shutter: a skinned or morphing mesh, for
/// motion blur. Each triangle's vertices (and corner normals, if it has them) are keyed at
/// evenly spaced shutter times, 0 (open) to 1 (closed), and interpolated linearly between keys,
/// so that a ray at time u meets the triangle as it is at u.
///
/// Rays are searched through a binary BVH over each triangle's swept bounds: the bounds of its
/// vertices at every key, which hold every interpolated triangle (a point interpolated between
/// two keys lies between its places at them). The search is scalar; it serves only the few
/// deforming meshes of a blurred frame (rigid meshes keep the SIMD kernels, math/motion.h).

#include <array>
#include <cstdint>
#include <vector>

#include "glint/core/ray.h"
#include "glint/geometry/triangle.h"
#include "glint/math/bbox.h"

namespace glint {

class DeformingMesh {
  public:
    using Corners = std::array<Vec3f, 3>;

    DeformingMesh() = default;
    /// `vertices[k][i]`: triangle i's corners at key k (at least two keys, each of the same
    /// size); `normals` likewise for the corner normals, or empty for triangles shaded flat.
    DeformingMesh(std::vector<std::vector<Corners>> vertices,
                  std::vector<std::vector<Corners>> normals = {});

    uint32_t size() const { return count_; }
    int keys() const { return keys_; }
    bool hasNormals() const { return !normals_.empty(); }

    /// Triangle `i` at shutter time u (clamped to [0, 1]).
    Triangle at(uint32_t i, float u) const { return toTriangle(lerp(vertices_, i, u)); }
    /// Triangle `i`'s corner normals at time u (hasNormals()).
    Corners normalsAt(uint32_t i, float u) const { return lerp(normals_, i, u); }
    /// Bounds of every triangle over the whole shutter.
    Bounds3f bounds() const { return nodes_.empty() ? Bounds3f() : nodes_.front().box; }

    /// The closest hit of `ray` at shutter time u with tMin < t < min(ray.tMax, hit.t), by
    /// the closerHit rule over triangle indices: fills `hit` (primId the triangle) and returns
    /// true if there is one.
    bool intersect(const TraversalRay& ray, float u, Hit& hit) const;
    /// Whether anything at time u lies strictly between tMin and tMax.
    bool occluded(const TraversalRay& ray, float u) const;

  private:
    struct Node {
        Bounds3f box;
        uint32_t first = 0;  ///< Leaf: its first triangle in order_; interior: the second child.
        uint32_t count = 0;  ///< Leaf: its triangles (> 0); interior: 0 (first child: next node).
    };
    static Triangle toTriangle(const Corners& c) { return {c[0], c[1], c[2]}; }
    Corners lerp(const std::vector<Corners>& keyed, uint32_t i, float u) const;
    uint32_t build(uint32_t begin, uint32_t end, const std::vector<Bounds3f>& boxes, int depth);
    template <bool kAnyHit>
    bool search(const TraversalRay& ray, float u, Hit& hit) const;

    std::vector<Corners> vertices_;  ///< Key k's triangle i at k * count_ + i.
    std::vector<Corners> normals_;   ///< Likewise, or empty.
    std::vector<Node> nodes_;        ///< Depth first; the root is node 0.
    std::vector<uint32_t> order_;    ///< Triangle indices, in leaf order.
    uint32_t count_ = 0;
    int keys_ = 0;
};

}  // namespace glint
