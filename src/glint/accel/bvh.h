#pragma once
/// Bounding volume hierarchy over a primitive set: binned surface-area-heuristic build, flat
/// depth-first node array, stack-based ordered traversal without allocation.

#include <cstdint>
#include <vector>

#include "glint/geometry/primitives.h"

namespace glint {

struct BvhNode {
    Bounds3f bounds;
    /// Interior: index of the second child (the first follows this node).
    /// Leaf: index of the first entry in the primitive index array.
    uint32_t offset = 0;
    uint16_t count = 0;  ///< Primitives in a leaf; 0 for interior nodes.
    uint8_t axis = 0;    ///< Split axis of an interior node.
};

struct BvhStats {
    uint32_t nodes = 0, leaves = 0, maxDepth = 0, maxLeafSize = 0;
    size_t bytes = 0;  ///< Nodes plus primitive index array.
};

class Bvh {
  public:
    /// Builds over `prims`, which must outlive the BVH (a reference is kept).
    void build(const Primitives& prims);

    /// Closest hit with tMin < t < min(ray.tMax, hit.t); fills `hit` and returns true if any.
    bool intersect(const Ray& ray, Hit& hit) const;
    /// Whether anything lies strictly between tMin and tMax (any hit, not the closest).
    bool occluded(const Ray& ray) const;

    const BvhStats& stats() const { return stats_; }
    const std::vector<BvhNode>& nodes() const { return nodes_; }

    /// Traversal stack depth bound; the builder never makes a deeper tree.
    static constexpr int kMaxDepth = 96;

  private:
    template <bool AnyHit>
    bool traverse(const TraversalRay& ray, Hit& hit) const;

    const Primitives* prims_ = nullptr;
    std::vector<BvhNode> nodes_;
    std::vector<uint32_t> primIndex_;
    BvhStats stats_;
};

}  // namespace glint
