// Building the BVH: primitive references, then 8-wide nodes grown top down from the SAH's
// decisions (bvh_build_sah.cpp), then the layout (bvh_build_flatten.cpp). Every phase runs on
// the caller's thread pool; none of them lets the thread count change the result.

#include "glint/accel/bvh_build.h"

#include <algorithm>
#include <array>
#include <utility>
#include <vector>

#include "glint/accel/bvh_build_sah.h"
#include "glint/accel/bvh_build_tree.h"
#include "glint/core/parallel.h"

namespace glint::bvh {
namespace builder {
namespace {

constexpr uint32_t kTaskThreshold = 8192;      // subtrees at least this big are tasks
constexpr uint32_t kParallelSplit = 1u << 15;  // splits this big are tasks within a round
constexpr uint32_t kRefsChunk = 1u << 16;      // primitives per chunk when making refs

/// Grows the tree over `refs`, reordering them so that every leaf is a range of them.
class Builder {
  public:
    Builder(LargeArray<PrimRef>& refs, ThreadPool& pool) : refs_(refs), pool_(pool) {}

    /// Builds the tree over `all`, the range of every ref; returns the root.
    ChildRef buildAll(const Range& all) {
        ChildRef root = subtree(all, 0);
        subtrees_.wait();
        return root;
    }

    const NodePool& nodes() const { return nodes_; }

  private:
    /// Bounds, centroid bounds and shape count of refs [begin, end).
    Range makeRange(uint32_t begin, uint32_t end) const {
        Range r;
        r.begin = begin;
        r.end = end;
        for (uint32_t i = begin; i < end; ++i) r.add(refs_[i]);
        return r;
    }

    Decision decide(const Range& r, uint32_t depth) const {
        return builder::decide(refs_.data(), r, depth, pool_);
    }

    /// Moves the refs of `r` for which `left` holds to the front, computing both sides' ranges
    /// on the way (no second pass over the data).
    template <typename Pred>
    std::pair<Range, Range> partitionBy(const Range& r, Pred left) {
        Range L, R;
        uint32_t i = r.begin, j = r.end;
        for (;;) {
            while (i < j && left(refs_[i])) L.add(refs_[i++]);
            while (i < j && !left(refs_[j - 1])) R.add(refs_[--j]);
            if (i >= j) break;
            std::swap(refs_[i], refs_[j - 1]);
            L.add(refs_[i++]);
            R.add(refs_[--j]);
        }
        L.begin = r.begin, L.end = i, R.begin = i, R.end = r.end;
        return {L, R};
    }

    /// Splits `r` as decided into two non-empty ranges.
    std::pair<Range, Range> split(const Range& r, const Decision& d) {
        std::pair<Range, Range> parts;
        if (d.kind == SplitKind::Sah) {
            Binning binning(r);
            int axis = d.axis, bin = d.bin;
            parts = partitionBy(r, [&](const PrimRef& p) { return binning.bin(p, axis) <= bin; });
        } else if (d.kind == SplitKind::Types) {
            parts = partitionBy(r, [](const PrimRef& p) { return p.shape == 0; });
        }
        if (parts.first.size() == 0 || parts.second.size() == 0) {
            // Median (or a safety net for a split that separated nothing): halve by count.
            uint32_t mid = r.begin + r.size() / 2;
            int axis = d.axis;
            std::nth_element(refs_.data() + r.begin, refs_.data() + mid, refs_.data() + r.end,
                             [axis](const PrimRef& a, const PrimRef& b) {
                                 return a.centroid2(axis) < b.centroid2(axis);
                             });
            parts = {makeRange(r.begin, mid), makeRange(mid, r.end)};
        }
        return parts;
    }

    static ChildRef makeLeaf(const Range& r) {
        return {kLeafBit | r.begin, r.size(), r.shapes != 0};
    }

    struct Slot {
        Range range;
        Decision decision;
        uint32_t depth;  ///< Binary splits above this range.
    };

    /// Builds the subtree over `r`; its large subtrees become tasks of `subtrees_`.
    ChildRef subtree(const Range& r, uint32_t depth) {
        Decision d = decide(r, depth);
        if (d.kind == SplitKind::Leaf) return makeLeaf(r);

        // Grow an 8-wide node in rounds: each round splits, largest area first, as many of the
        // splittable children as still fit. The splits of a round are independent, so large
        // ones are tasks; the rule does not depend on the thread count.
        std::array<Slot, kWidth> slots;
        slots[0] = {r, d, depth};
        uint32_t count = 1;
        while (count < kWidth) {
            std::array<uint32_t, kWidth> order;
            uint32_t candidates = 0;
            for (uint32_t i = 0; i < count; ++i)
                if (slots[i].decision.kind != SplitKind::Leaf) order[candidates++] = i;
            if (candidates == 0) break;
            std::stable_sort(order.begin(), order.begin() + candidates,
                             [&](uint32_t a, uint32_t b) {
                                 return slots[a].range.bounds.area() > slots[b].range.bounds.area();
                             });
            uint32_t take = std::min(candidates, kWidth - count);
            std::array<std::pair<Slot, Slot>, kWidth> halves;
            auto splitOne = [&](uint32_t j) {
                const Slot& s = slots[order[j]];
                auto [left, right] = split(s.range, s.decision);
                halves[j] = {{left, decide(left, s.depth + 1), s.depth + 1},
                             {right, decide(right, s.depth + 1), s.depth + 1}};
            };
            TaskGroup splits(pool_);
            for (uint32_t j = 0; j < take; ++j) {
                if (j + 1 < take && slots[order[j]].range.size() >= kParallelSplit)
                    splits.run([&splitOne, j] { splitOne(j); });
                else
                    splitOne(j);
            }
            splits.wait();
            for (uint32_t j = 0; j < take; ++j) {
                slots[order[j]] = halves[j].first;
                slots[count++] = halves[j].second;
            }
        }

        uint32_t id = nodes_.allocate();
        TmpNode& node = nodes_[id];
        node.count = count;
        for (uint32_t i = 0; i < count; ++i) node.bounds[i] = slots[i].range.bounds.bounds3();
        for (uint32_t i = 0; i < count; ++i) {
            const Slot& s = slots[i];
            if (s.decision.kind == SplitKind::Leaf) {
                node.child[i] = makeLeaf(s.range);
            } else if (s.range.size() >= kTaskThreshold) {
                // Every large subtree is a task, whichever thread is free takes it: a split
                // handed out only to idle threads left them waiting while one thread built
                // most of the tree.
                subtrees_.run(
                    [this, id, i, s] { nodes_[id].child[i] = subtree(s.range, s.depth); });
            } else {
                node.child[i] = subtree(s.range, s.depth);
            }
        }
        return {id, 0};
    }

    LargeArray<PrimRef>& refs_;
    ThreadPool& pool_;
    NodePool nodes_;
    TaskGroup subtrees_{pool_};  // last: destroyed (waiting for its tasks) before the nodes
};

}  // namespace
}  // namespace builder

BuildSummary build(const Primitives& prims, ThreadPool& pool, BvhData& out) {
    using namespace builder;
    out = BvhData{};
    BuildSummary summary;
    // Planes and moving primitives are not in the tree (Bvh keeps them beside it).
    std::vector<uint32_t> still;  // the ids in the tree, when some primitives move
    if (prims.hasMotion())
        for (uint32_t id = 0; id < prims.boundedCount(); ++id)
            if (!prims.motion(id)) still.push_back(id);
    const uint32_t n =
        prims.hasMotion() ? static_cast<uint32_t>(still.size()) : prims.boundedCount();
    if (n == 0) return summary;

    // The refs, and the range of them all, by chunks (boxes are unions: the same either way).
    LargeArray<PrimRef> refs(n);
    std::vector<Range> parts((n + kRefsChunk - 1) / kRefsChunk);
    parallelFor(pool, 0, n, kRefsChunk, [&](size_t first, size_t last) {
        Range& part = parts[first / kRefsChunk];
        for (auto i = static_cast<uint32_t>(first); i < last; ++i) {
            const uint32_t id = still.empty() ? i : still[i];
            Bounds3f b = prims.stillBounds(id);
            refs[i] = {{b.lo.x, b.lo.y, b.lo.z},
                       id,
                       {b.hi.x, b.hi.y, b.hi.z},
                       id < prims.triangleCount() ? 0u : 1u};
            part.add(refs[i]);
        }
    });
    Range all;
    all.end = n;
    for (const Range& p : parts) {
        all.bounds.extend(p.bounds);
        all.centroids.extend(p.centroids);
        all.shapes += p.shapes;
    }
    summary.bounds = all.bounds.bounds3();

    Builder builder(refs, pool);
    ChildRef root = builder.buildAll(all);
    out.root = flatten(root, builder.nodes(), refs, prims, pool, out, summary);
    return summary;
}

}  // namespace glint::bvh
