#pragma once
/// The memory layout of Glint's BVH, shared by the builder and the traversal kernels.
///
/// An 8-wide tree: each node holds the boxes of up to eight children, stored per axis and per
/// child so that one SIMD instruction tests a ray against all eight. Leaves hold blocks of
/// four triangles, vertex coordinates again stored per component and per lane, or a short
/// run of shapes (spheres, boxes, cylinders, cones, disks: their float search records).
/// Everything is in flat arrays in depth-first order; children are 32-bit references.
/// Planes are unbounded: they are not in the tree but in a list beside it. Instances of shared
/// meshes are shape records whose test searches the mesh's own tree (BvhData::meshes).

#include <cstddef>
#include <cstdint>
#include <vector>

#include "glint/core/huge_pages.h"
#include "glint/geometry/deforming_mesh.h"
#include "glint/geometry/plane.h"
#include "glint/geometry/shape_search.h"
#include "glint/math/bbox.h"
#include "glint/math/motion.h"

namespace glint::bvh {

constexpr int kWidth = 8;  ///< Children per node.
constexpr int kLanes = 4;  ///< Triangles per leaf block.

/// A child reference. Interior: the node index (bit 31 clear). Leaf: bit 31 set, bits 26-29
/// a count (0 to 15), bits 0-25 an index `first`, and
///
///   bit 30 set    a sphere leaf: `count` spheres, records shapes[first, first + count)
///   bit 30 clear  count >= 1: `count` blocks of four triangles, tris[first, first + count);
///                 count 0: a leaf of other shapes (boxes, cylinders, cones, disks, perhaps
///                 spheres among them): shapeRuns[first] names its records
///
/// Traversal tests bit 30 first, so sphere leaves cost one test as they always did; triangle
/// leaves are told from shape runs by their count, a test their loop over blocks makes anyway.
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
/// A leaf of shapes other than only spheres (a leaf, not a sphere leaf, of count 0).
constexpr bool isShapeRunLeaf(NodeRef r) { return !isSphereLeaf(r) && leafCount(r) == 0; }
constexpr NodeRef makeTriangleLeaf(uint32_t first, uint32_t blocks) {
    return kLeafBit | (blocks << kCountShift) | first;
}
constexpr NodeRef makeSphereLeaf(uint32_t first, uint32_t count) {
    return kLeafBit | kSphereBit | (count << kCountShift) | first;
}
constexpr NodeRef makeShapeRunLeaf(uint32_t run) { return kLeafBit | run; }

/// The records of a leaf of shapes: shapes[first, first + count).
struct ShapeRun {
    uint32_t first, count;
};

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
    LargeVector<ShapeSearch> shapes;  ///< Sphere and shape leaf items, in leaf order.
    LargeVector<uint32_t> shapeIds;   ///< Their primitive ids.
    std::vector<ShapeRun> shapeRuns;  ///< Leaves of shapes other than only spheres.
    /// Unbounded primitives, tested beside the tree by Bvh (the kernels never see them).
    std::vector<PlaneSearch> planes;
    std::vector<uint32_t> planeIds;
    /// The trees of the shared meshes that instance records name (ShapeSearch::mesh()); owned
    /// by their own Bvh objects, traversed with the same kernels.
    std::vector<const BvhData*> meshes;
    /// For each of `meshes`: its deformation over the shutter (searched in place of its tree,
    /// at the calling thread's shutter time), or null when it is still.
    std::vector<const DeformingMesh*> deforming;
    /// Moving primitives (Primitives::setMotion), tested beside the tree by Bvh at the calling
    /// thread's shutter time: each with the bounds it sweeps, its record where it was added
    /// and its path.
    struct Moving {
        uint32_t id;
        Bounds3f bounds;
        ShapeSearch search;
        MotionPath path;
    };
    std::vector<Moving> moving;

    size_t bytes() const {
        return nodes.size() * sizeof(Node8) + tris.size() * sizeof(Tri4) +
               shapes.size() * sizeof(ShapeSearch) + shapeIds.size() * sizeof(uint32_t) +
               shapeRuns.size() * sizeof(ShapeRun) + planes.size() * sizeof(PlaneSearch) +
               planeIds.size() * sizeof(uint32_t);
    }
};

}  // namespace glint::bvh
