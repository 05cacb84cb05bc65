// The builder's last phase: the grown tree laid out in flat arrays, depth first (bvh_layout.h).

#include <algorithm>
#include <array>
#include <limits>
#include <stdexcept>

#include "glint/accel/bvh_build_tree.h"
#include "glint/core/parallel.h"

namespace glint::bvh::builder {
namespace {

/// Sizes of a laid-out subtree, and a place to write one.
struct Layout {
    uint32_t nodes = 0, tris = 0, shapes = 0, runs = 0;

    Layout& operator+=(const Layout& o) {
        nodes += o.nodes, tris += o.tris, shapes += o.shapes, runs += o.runs;
        return *this;
    }
};

/// Lays subtrees out into `out`, creating leaf blocks as they come. Subtrees can be laid out
/// concurrently: each writes at positions computed beforehand, so the layout is the same as a
/// single depth-first pass.
class Flattener {
  public:
    Flattener(const NodePool& nodes, const LargeArray<PrimRef>& refs, const Primitives& prims,
              BvhData& out)
        : nodes_(nodes), refs_(refs), prims_(prims), out_(out) {}

    /// What `c` occupies once laid out.
    Layout size(const ChildRef& c) const {
        if (c.ref & kLeafBit) {
            if (!c.shapes) return Layout{0, (c.size + kLanes - 1) / kLanes, 0, 0};
            return Layout{0, 0, c.size, spheresOnly(c) ? 0u : 1u};
        }
        Layout l{1, 0, 0, 0};
        const TmpNode& tmp = nodes_[c.ref];
        for (uint32_t i = 0; i < tmp.count; ++i) l += size(tmp.child[i]);
        return l;
    }

    /// Sizes the output arrays for `total`.
    void allocate(const Layout& total) {
        out_.nodes.resize(total.nodes);
        out_.tris.resize(total.tris);
        out_.shapes.resize(total.shapes);
        out_.shapeIds.resize(total.shapes);
        out_.shapeRuns.resize(total.runs);
    }

    /// Lays out `c`, `depth` levels of nodes below the root, starting at `at` (which advances);
    /// returns its final reference.
    NodeRef flatten(const ChildRef& c, Layout& at, uint32_t depth, BuildSummary& summary) {
        if (c.ref & kLeafBit) return leaf(c, at, summary);
        summary.maxDepth = std::max(summary.maxDepth, depth + 1);
        uint32_t index = at.nodes++;
        if (index >= kLeafBit) throw std::length_error("BVH too large");
        const TmpNode& tmp = nodes_[c.ref];
        writeNode(index, tmp);
        for (uint32_t i = 0; i < tmp.count; ++i)
            out_.nodes[index].child[i] = flatten(tmp.child[i], at, depth + 1, summary);
        return index;
    }

    /// Writes the boxes of node `index`; its children are filled in as they are laid out.
    void writeNode(uint32_t index, const TmpNode& tmp) {
        Node8& n = out_.nodes[index];
        for (uint32_t i = 0; i < kWidth; ++i) {
            bool used = i < tmp.count;
            for (int a = 0; a < 3; ++a) {
                n.lo[a][i] = used ? tmp.bounds[i].lo[a] : std::numeric_limits<float>::infinity();
                n.hi[a][i] = used ? tmp.bounds[i].hi[a] : -std::numeric_limits<float>::infinity();
            }
            n.child[i] = kEmpty;
        }
    }

  private:
    NodeRef leaf(const ChildRef& c, Layout& at, BuildSummary& summary) {
        const uint32_t begin = c.ref & ~kLeafBit, n = c.size, end = begin + n;
        summary.leaves++;
        summary.maxLeafSize = std::max(summary.maxLeafSize, n);
        if (c.shapes) {
            uint32_t first = at.shapes;
            check(first, n);
            for (uint32_t i = begin; i < end; ++i, ++at.shapes) {
                uint32_t id = refs_[i].id;
                out_.shapes[at.shapes] = prims_.shapeSearch(id);
                out_.shapeIds[at.shapes] = id;
            }
            if (spheresOnly(c)) return makeSphereLeaf(first, n);
            uint32_t run = at.runs++;
            check(run, 1);
            out_.shapeRuns[run] = {first, n};
            return makeShapeRunLeaf(run);
        }
        uint32_t first = at.tris;
        uint32_t blocks = (n + kLanes - 1) / kLanes;
        check(first, blocks);
        constexpr float nan = std::numeric_limits<float>::quiet_NaN();
        for (uint32_t b = 0; b < blocks; ++b) {
            Tri4& t = out_.tris[at.tris++];
            for (int lane = 0; lane < kLanes; ++lane) {
                uint32_t i = begin + b * kLanes + static_cast<uint32_t>(lane);
                bool used = i < end;
                const Triangle* tri = used ? &prims_.triangle(refs_[i].id) : nullptr;
                for (int k = 0; k < 3; ++k) {
                    t.v0[k][lane] = used ? tri->v0[k] : nan;
                    t.v1[k][lane] = used ? tri->v1[k] : nan;
                    t.v2[k][lane] = used ? tri->v2[k] : nan;
                }
                t.id[lane] = used ? refs_[i].id : kEmpty;
            }
        }
        return makeTriangleLeaf(first, blocks);
    }

    /// A leaf of shapes that holds spheres only (traversal calls the sphere test directly).
    bool spheresOnly(const ChildRef& c) const {
        const uint32_t begin = c.ref & ~kLeafBit;
        for (uint32_t i = begin; i < begin + c.size; ++i)
            if (!prims_.isSphere(refs_[i].id)) return false;
        return true;
    }

    static void check(uint32_t first, uint32_t count) {
        if (count > kMaxLeafItems || first + count > kMaxItemIndex)
            throw std::length_error("BVH leaf data exceeds the layout's limits");
    }

    const NodePool& nodes_;
    const LargeArray<PrimRef>& refs_;
    const Primitives& prims_;
    BvhData& out_;
};

}  // namespace

NodeRef flatten(const ChildRef& root, const NodePool& nodes, const LargeArray<PrimRef>& refs,
                const Primitives& prims, ThreadPool& pool, BvhData& out, BuildSummary& summary) {
    Flattener f(nodes, refs, prims, out);
    Layout at;
    if (root.ref & kLeafBit) {
        f.allocate(f.size(root));
        return f.flatten(root, at, 0, summary);
    }
    // The sizes of the root's subtrees give the whole's and where each subtree goes.
    const TmpNode& tmp = nodes[root.ref];
    std::array<Layout, kWidth> sizes;
    parallelFor(pool, 0, tmp.count, 1, [&](size_t first, size_t last) {
        for (size_t i = first; i < last; ++i) sizes[i] = f.size(tmp.child[i]);
    });
    Layout total{1, 0, 0, 0};
    for (uint32_t i = 0; i < tmp.count; ++i) total += sizes[i];
    f.allocate(total);
    if (pool.threads() == 1) return f.flatten(root, at, 0, summary);

    // The root here, its subtrees on any thread, each from where the ones before it end.
    summary.maxDepth = 1;
    f.writeNode(at.nodes++, tmp);
    std::array<Layout, kWidth> starts;
    std::array<BuildSummary, kWidth> parts{};
    for (uint32_t i = 0; i < tmp.count; ++i) {
        starts[i] = at;
        at += sizes[i];
    }
    parallelFor(pool, 0, tmp.count, 1, [&](size_t first, size_t last) {
        for (size_t i = first; i < last; ++i)
            out.nodes[0].child[i] = f.flatten(tmp.child[i], starts[i], 1, parts[i]);
    });
    for (uint32_t i = 0; i < tmp.count; ++i) {
        summary.leaves += parts[i].leaves;
        summary.maxDepth = std::max(summary.maxDepth, parts[i].maxDepth);
        summary.maxLeafSize = std::max(summary.maxLeafSize, parts[i].maxLeafSize);
    }
    return 0;
}

}  // namespace glint::bvh::builder
