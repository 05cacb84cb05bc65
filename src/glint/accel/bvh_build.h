#pragma once
/// Building Glint's 8-wide BVH (see bvh_layout.h). The builder's files, in the order it runs:
/// bvh_build_refs.h (primitive references, box arithmetic), bvh_build_sah.{h,cpp} (leaf or
/// split: binned SAH), bvh_build.cpp (nodes grown 8 wide, in parallel tasks),
/// bvh_build_tree.h and bvh_build_flatten.cpp (the grown tree, laid out depth first).

#include <cstdint>

#include "glint/accel/bvh_layout.h"
#include "glint/geometry/primitives.h"

namespace glint {
class ThreadPool;
}

namespace glint::bvh {

struct BuildSummary {
    uint32_t leaves = 0;
    uint32_t maxDepth = 0;     ///< Levels of 8-wide nodes below the root.
    uint32_t maxLeafSize = 0;  ///< Primitives in the largest leaf.
    Bounds3f bounds;           ///< Of all bounded primitives (planes are not in the tree).
};

/// Deepest tree the builder makes (levels of 8-wide nodes). Traversal stacks hold
/// 7 * kMaxDepth + 1 entries: at most seven pushes per level.
constexpr uint32_t kMaxDepth = 80;

/// Builds over the bounded primitives of `prims` (all but planes, which it leaves to Bvh)
/// with binned SAH on the threads of `pool`; the result does not depend on how many there are.
/// Replaces `out`. Throws std::length_error past the layout's limits (2^26 leaf items).
BuildSummary build(const Primitives& prims, ThreadPool& pool, BvhData& out);

/// Refits `data`, built by build() over primitives of the same ids, to `prims` (the same
/// primitives moved: the next frame of an animation): every leaf's items are read again from
/// `prims`, and every box is recomputed from them, children before parents. The tree keeps its
/// shape (bvh_refit.cpp). Refitting to the primitives it was built over gives exactly what
/// the build gave. Returns the bounds of the tree's primitives.
Bounds3f refit(const Primitives& prims, BvhData& data);

/// The summed surface areas of every box in the tree's nodes over the root's: the quantity a
/// refit lets grow (a measure of the tree's cost to search, as SAH's); 0 for a tree of no
/// nodes.
double relativeArea(const BvhData& data);

}  // namespace glint::bvh
