#include <limits>

#include "glint/accel/bvh_build.h"

namespace glint::bvh {
namespace {

/// The bounds of leaf `r`'s items, as the builder took them (Primitives::stillBounds).
Bounds3f leafBounds(const Primitives& prims, const BvhData& d, NodeRef r) {
    Bounds3f b;
    const uint32_t first = leafFirst(r);
    if (isSphereLeaf(r) || isShapeRunLeaf(r)) {
        const ShapeRun run = isSphereLeaf(r) ? ShapeRun{first, leafCount(r)} : d.shapeRuns[first];
        for (uint32_t i = run.first; i < run.first + run.count; ++i) {
            b.extend(prims.stillBounds(d.shapeIds[i]));
        }
        return b;
    }
    for (uint32_t t = first; t < first + leafCount(r); ++t)
        for (uint32_t id : d.tris[t].id) {
            if (id == kEmpty) continue;
            b.extend(prims.stillBounds(id));
        }
    return b;
}

/// The bounds of node `index`'s children (its boxes, already fitted).
Bounds3f nodeBounds(const BvhData& d, uint32_t index) {
    Bounds3f b;
    const Node8& n = d.nodes[index];
    for (int i = 0; i < kWidth; ++i) {
        if (n.child[i] == kEmpty) continue;
        b.extend(Vec3f(n.lo[0][i], n.lo[1][i], n.lo[2][i]));
        b.extend(Vec3f(n.hi[0][i], n.hi[1][i], n.hi[2][i]));
    }
    return b;
}

}  // namespace

Bounds3f refit(const Primitives& prims, BvhData& d) {
    // The leaves' items, read again: triangles' vertices, shapes' search records.
    for (Tri4& t : d.tris)
        for (int lane = 0; lane < kLanes; ++lane) {
            if (t.id[lane] == kEmpty) continue;
            const Triangle& tri = prims.triangle(t.id[lane]);
            for (int k = 0; k < 3; ++k) {
                t.v0[k][lane] = tri.v0[k];
                t.v1[k][lane] = tri.v1[k];
                t.v2[k][lane] = tri.v2[k];
            }
        }
    for (size_t i = 0; i < d.shapes.size(); ++i) d.shapes[i] = prims.shapeSearch(d.shapeIds[i]);
    if (d.root == kEmpty) return {};
    if (isLeaf(d.root)) return leafBounds(prims, d, d.root);
    // Depth first, a node comes before its children: from the last node back, every child's
    // box is known when its parent's is fitted.
    for (size_t index = d.nodes.size(); index-- > 0;) {
        Node8& n = d.nodes[index];
        for (int i = 0; i < kWidth; ++i) {
            const NodeRef c = n.child[i];
            if (c == kEmpty) continue;
            const Bounds3f b = isLeaf(c) ? leafBounds(prims, d, c) : nodeBounds(d, c);
            for (int a = 0; a < 3; ++a) {
                n.lo[a][i] = b.lo[a];
                n.hi[a][i] = b.hi[a];
            }
        }
    }
    return nodeBounds(d, 0);
}

double relativeArea(const BvhData& d) {
    if (d.nodes.empty()) return 0;
    double sum = 0;
    for (const Node8& n : d.nodes)
        for (int i = 0; i < kWidth; ++i) {
            if (n.child[i] == kEmpty) continue;
            const Bounds3f b{Vec3f(n.lo[0][i], n.lo[1][i], n.lo[2][i]),
                             Vec3f(n.hi[0][i], n.hi[1][i], n.hi[2][i])};
            sum += b.area();
        }
    const double root = nodeBounds(d, 0).area();
    return root > 0 ? sum / root : 0;
}

}  // namespace glint::bvh
