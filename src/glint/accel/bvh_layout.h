#pragma once
/// The memory layout of Glint's BVH, shared by the builder and the traversal kernels.
///
/// An 8-wide tree: each node holds the boxes of up to eight children, stored per axis and per
/// child so that one SIMD instruction tests a ray against all eight. Leaves hold blocks of
/// four triangles, vertex coordinates again stored per component and per lane, or a short
/// run of spheres. Everything is in flat arrays in depth-first order; children are 32-bit
/// references.

#include <cstddef>
#include <cstdint>

#include "glint/core/huge_pages.h"
#include "glint/geometry/sphere.h"

namespace glint::bvh {

constexpr int kWidth = 8;  ///< Children per node.
constexpr int kLanes = 4;  ///< Triangles per leaf block.

/// A child reference. Interior: the node index (bit 31 clear). Leaf: bit 31 set, bit 30 set
/// for spheres, bits 26-29 the number of items (triangle blocks or spheres, 1 to 15), bits 0-25
/// the index of the first item.
using NodeRef = uint32_t;
constexpr NodeRef kEmpty = 0xffffffffu;  ///< An unused child slot (its box is empty).
constexpr uint32_t kLeafBit = 1u << 31;
constexpr uint32_t kSphereBit = 1u << 30;
constexpr int kCountShift = 26;
constexpr uint32_t kMaxLeafItems = 15;
constexpr uint32_t kMaxItemIndex = (1u << kCountShift) - 1;

constexpr bool isLeaf(NodeRef r) { return (r & kLeafBit) != 0; }
constexpr bool isSphereLeaf(NodeRef r) { return (r & kSphereBit) != 0; }
constexpr uint32_t leafFirst(NodeRef r) { return r & kMaxItemIndex; }
constexpr uint32_t leafCount(NodeRef r) { return (r >> kCountShift) & 15u; }
constexpr NodeRef makeLeaf(bool spheres, uint32_t first, uint32_t count) {
    return kLeafBit | (spheres ? kSphereBit : 0u) | (count << kCountShift) | first;
}

struct alignas(32) Node8 {
    float lo[3][kWidth];  ///< lo[axis][child]; empty slots hold +inf.
    float hi[3][kWidth];  ///< hi[axis][child]; empty slots hold -inf.
    NodeRef child[kWidth];
};
static_assert(sizeof(Node8) == 224);
static_assert(offsetof(Node8, hi) == 3 * kWidth * sizeof(float));  // kernels index lo then hi

/// Four triangles for the watertight test; unused lanes hold NaN vertices (never hit).
struct alignas(16) Tri4 {
    float v0[3][kLanes], v1[3][kLanes], v2[3][kLanes];  ///< [component][lane]
    uint32_t id[kLanes];                                ///< Primitive ids.
};
static_assert(sizeof(Tri4) == 160);

/// Everything traversal reads.
struct BvhData {
    NodeRef root = kEmpty;  ///< Node 0 when interior; a leaf for tiny scenes.
    LargeVector<Node8> nodes;
    LargeVector<Tri4> tris;
    LargeVector<SphereSearch> spheres;  ///< Sphere leaf items, in leaf order.
    LargeVector<uint32_t> sphereIds;    ///< Their primitive ids.

    size_t bytes() const {
        return nodes.size() * sizeof(Node8) + tris.size() * sizeof(Tri4) +
               spheres.size() * sizeof(SphereSearch) + sphereIds.size() * sizeof(uint32_t);
    }
};

}  // namespace glint::bvh
