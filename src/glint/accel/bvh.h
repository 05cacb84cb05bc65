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

struct BvhBuildOptions {
    int threads = 0;  ///< Build threads; 0 means all hardware threads.
};

struct BvhStats {
    uint32_t nodes = 0, leaves = 0, maxDepth = 0, maxLeafSize = 0;
    size_t bytes = 0;  ///< Everything traversal reads: nodes plus leaf data.
    double buildSeconds = 0;
};

class Bvh {
  public:
    /// Builds over `prims`, which must outlive the BVH (a reference is kept).
    void build(const Primitives& prims, const BvhBuildOptions& options = {});

    /// Closest hit with tMin < t < min(ray.tMax, hit.t); fills `hit` and returns true if any.
    /// Among hits at exactly the same distance the lowest primitive id wins, so the result
    /// does not depend on traversal order.
    bool intersect(const Ray& ray, Hit& hit) const { return intersect(TraversalRay(ray), hit); }
    bool intersect(const TraversalRay& ray, Hit& hit) const;
    /// Whether anything lies strictly between tMin and tMax (any hit, not the closest).
    bool occluded(const Ray& ray) const { return occluded(TraversalRay(ray)); }
    bool occluded(const TraversalRay& ray) const;
    /// Closest hits of the active rays of a packet; the same results as `intersect` per ray.
    void intersect8(const RayPacket8& rays, HitPacket8& hits) const;

    /// The instruction set the traversal kernels use ("avx2" or "portable").
    static const char* isa();

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
