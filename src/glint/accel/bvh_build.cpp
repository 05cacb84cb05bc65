#include "glint/accel/bvh_build.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <condition_variable>
#include <functional>
#include <limits>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <thread>

namespace glint::bvh {
namespace {

constexpr int kBins = 16;
constexpr uint32_t kMaxLeafTriangles = 2 * kLanes;  // two blocks
constexpr uint32_t kMaxLeafSpheres = 4;
constexpr float kTraversalCost = 1;  // a node visit, relative to one triangle block or sphere
constexpr uint32_t kMedianSplitDepth = 48;  // deeper binary splits halve by count
constexpr uint32_t kTaskThreshold = 8192;   // subtrees at least this big may go to idle threads
constexpr float kInf = std::numeric_limits<float>::infinity();

/// A primitive's bounds during the build; lo + hi stands for its centroid (twice it).
struct PrimRef {
    Vec3f lo;
    uint32_t id;
    Vec3f hi;
    uint32_t sphere;  ///< 1 for spheres, 0 for triangles.

    Vec3f centroid2() const { return lo + hi; }
};

struct Range {
    uint32_t begin = 0, end = 0, spheres = 0;
    Bounds3f bounds, centroids;  ///< Centroids as lo + hi.

    uint32_t size() const { return end - begin; }
    uint32_t triangles() const { return size() - spheres; }
};

/// Intersection cost of a leaf: one unit per triangle block and per sphere.
float leafCost(uint32_t triangles, uint32_t spheres) {
    return static_cast<float>((triangles + kLanes - 1) / kLanes + spheres);
}

bool fitsOneLeaf(const Range& r) {
    return r.spheres == 0 ? r.size() <= kMaxLeafTriangles
                          : (r.spheres == r.size() && r.size() <= kMaxLeafSpheres);
}

enum class SplitKind { Leaf, Sah, Median, Types };

struct Decision {
    SplitKind kind = SplitKind::Leaf;
    int axis = 0, bin = 0;
};

/// Ranges of the flat PrimRef array; leaves are recorded here and laid out after the build.
struct LeafRecord {
    uint32_t begin, end;
};

/// An 8-wide node while building: children are tmp node ids or leaf record ids (kLeafBit).
struct TmpNode {
    Bounds3f bounds[kWidth];
    uint32_t child[kWidth];
    uint32_t count = 0;
};

/// Nodes allocated from many threads: fixed-size chunks, never moved.
class NodePool {
  public:
    uint32_t allocate() {
        uint32_t id = next_.fetch_add(1, std::memory_order_relaxed);
        uint32_t chunk = id >> kChunkBits;
        if (chunk >= kMaxChunks) throw std::length_error("BVH too large");
        if (!ready_[chunk].load(std::memory_order_acquire)) {
            std::lock_guard lock(mutex_);
            if (!ready_[chunk].load(std::memory_order_relaxed)) {
                chunks_[chunk] = std::make_unique<TmpNode[]>(size_t{1} << kChunkBits);
                ready_[chunk].store(true, std::memory_order_release);
            }
        }
        return id;
    }
    TmpNode& operator[](uint32_t id) { return chunks_[id >> kChunkBits][id & kChunkMask]; }
    uint32_t size() const { return next_.load(); }

  private:
    static constexpr int kChunkBits = 12;
    static constexpr uint32_t kChunkMask = (1u << kChunkBits) - 1;
    static constexpr uint32_t kMaxChunks = 1u << 19;
    std::atomic<uint32_t> next_{0};
    std::mutex mutex_;
    std::unique_ptr<std::unique_ptr<TmpNode[]>[]> chunks_ =
        std::make_unique<std::unique_ptr<TmpNode[]>[]>(kMaxChunks);
    std::unique_ptr<std::atomic<bool>[]> ready_ = std::make_unique<std::atomic<bool>[]>(kMaxChunks);
};

/// Runs tasks on a fixed set of threads until none is queued or running.
class TaskPool {
  public:
    explicit TaskPool(int threads) : threads_(threads) {}

    bool hasIdleWorker() const { return idle_.load(std::memory_order_relaxed) > 0; }

    void push(std::function<void()> task) {
        std::lock_guard lock(mutex_);
        tasks_.push_back(std::move(task));
        ++pending_;
        wake_.notify_one();
    }

    void run() {
        std::vector<std::thread> workers;
        for (int i = 1; i < threads_; ++i) workers.emplace_back([this] { work(); });
        work();
        for (auto& w : workers) w.join();
        if (error_) std::rethrow_exception(error_);
    }

  private:
    void work() {
        std::unique_lock lock(mutex_);
        for (;;) {
            while (tasks_.empty() && pending_ > 0) {
                idle_.fetch_add(1, std::memory_order_relaxed);
                wake_.wait(lock);
                idle_.fetch_sub(1, std::memory_order_relaxed);
            }
            if (tasks_.empty()) return;  // nothing queued or running: done
            std::function<void()> task = std::move(tasks_.back());
            tasks_.pop_back();
            lock.unlock();
            try {
                task();
            } catch (...) {
                std::lock_guard errLock(errorMutex_);
                if (!error_) error_ = std::current_exception();
            }
            lock.lock();
            if (--pending_ == 0) wake_.notify_all();
        }
    }

    int threads_;
    std::mutex mutex_, errorMutex_;
    std::condition_variable wake_;
    std::vector<std::function<void()>> tasks_;
    int pending_ = 0;
    std::atomic<int> idle_{0};
    std::exception_ptr error_;
};

class Builder {
  public:
    Builder(std::vector<PrimRef>& refs, int threads) : refs_(refs), leaves_(refs.size()) {
        if (threads > 1) pool_ = std::make_unique<TaskPool>(threads);
    }

    /// Builds the tree over all refs; returns the root (tmp node id or leaf record id).
    uint32_t buildAll() {
        Range all = makeRange(0, static_cast<uint32_t>(refs_.size()));
        uint32_t root = kEmpty;
        if (pool_) {
            pool_->push([&] { root = subtree(all, 0, 0); });
            pool_->run();
        } else {
            root = subtree(all, 0, 0);
        }
        return root;
    }

    NodePool& nodes() { return nodes_; }
    const LeafRecord& leaf(uint32_t id) const { return leaves_[id]; }
    uint32_t leafCount() const { return leafCount_.load(); }
    uint32_t maxDepth() const { return maxDepth_.load(); }

  private:
    /// Bounds, centroid bounds and sphere count of refs [begin, end).
    Range makeRange(uint32_t begin, uint32_t end) const {
        Range r;
        r.begin = begin;
        r.end = end;
        for (uint32_t i = begin; i < end; ++i) {
            const PrimRef& p = refs_[i];
            r.bounds.extend(p.lo);
            r.bounds.extend(p.hi);
            r.centroids.extend(p.centroid2());
            r.spheres += p.sphere;
        }
        return r;
    }

    static int binOf(float c, float lo, float scale) {
        int b = static_cast<int>((c - lo) * scale);
        return std::clamp(b, 0, kBins - 1);
    }

    /// Leaf, or how to split: binned SAH over the three axes, else halving by count.
    Decision decide(const Range& r, uint32_t depth) const {
        uint32_t n = r.size();
        if (n <= 1) return {};
        bool mixed = r.spheres != 0 && r.spheres != n;
        if (depth >= kMedianSplitDepth) {
            if (fitsOneLeaf(r)) return {};
            return {mixed ? SplitKind::Types : SplitKind::Median, r.centroids.longestAxis(), 0};
        }

        struct Bin {
            Bounds3f bounds;
            uint32_t triangles = 0, spheres = 0;
        };
        std::array<std::array<Bin, kBins>, 3> bins{};
        Vec3f extent = r.centroids.diagonal(), scale;
        for (int a = 0; a < 3; ++a) scale[a] = extent[a] > 0 ? kBins / extent[a] : 0;
        for (uint32_t i = r.begin; i < r.end; ++i) {
            const PrimRef& p = refs_[i];
            Vec3f c = p.centroid2();
            for (int a = 0; a < 3; ++a) {
                Bin& b = bins[a][binOf(c[a], r.centroids.lo[a], scale[a])];
                b.bounds.extend(p.lo);
                b.bounds.extend(p.hi);
                b.triangles += 1 - p.sphere;
                b.spheres += p.sphere;
            }
        }

        float bestCost = kInf;
        int bestAxis = -1, bestBin = 0;
        for (int a = 0; a < 3; ++a) {
            if (!(extent[a] > 0)) continue;
            std::array<float, kBins> right{};
            Bounds3f acc;
            uint32_t tris = 0, sph = 0;
            for (int b = kBins - 1; b > 0; --b) {
                acc.extend(bins[a][b].bounds);
                tris += bins[a][b].triangles;
                sph += bins[a][b].spheres;
                right[b] = tris + sph ? acc.area() * leafCost(tris, sph) : 0;
            }
            acc = {};
            tris = sph = 0;
            for (int b = 0; b < kBins - 1; ++b) {
                acc.extend(bins[a][b].bounds);
                tris += bins[a][b].triangles;
                sph += bins[a][b].spheres;
                uint32_t left = tris + sph;
                if (left == 0 || left == n) continue;
                float cost = acc.area() * leafCost(tris, sph) + right[b + 1];
                if (cost < bestCost) bestCost = cost, bestAxis = a, bestBin = b;
            }
        }

        float area = r.bounds.area();
        float splitCost = bestAxis < 0 ? kInf : kTraversalCost + bestCost / area;
        if (fitsOneLeaf(r) && !(splitCost < leafCost(r.triangles(), r.spheres))) return {};
        if (bestAxis >= 0) return {SplitKind::Sah, bestAxis, bestBin};
        // All centroids coincide (or the areas are degenerate): halve, separating types first.
        if (mixed) return {SplitKind::Types, 0, 0};
        if (fitsOneLeaf(r)) return {};
        return {SplitKind::Median, r.centroids.longestAxis(), 0};
    }

    /// Splits `r` as decided; returns the split point.
    uint32_t partition(const Range& r, const Decision& d) {
        PrimRef* first = refs_.data() + r.begin;
        PrimRef* last = refs_.data() + r.end;
        PrimRef* mid = nullptr;
        switch (d.kind) {
            case SplitKind::Sah: {
                float lo = r.centroids.lo[d.axis];
                float scale = kBins / r.centroids.diagonal()[d.axis];
                int axis = d.axis, bin = d.bin;
                mid = std::partition(first, last, [&](const PrimRef& p) {
                    return binOf(p.centroid2()[axis], lo, scale) <= bin;
                });
                break;
            }
            case SplitKind::Types:
                mid = std::partition(first, last, [](const PrimRef& p) { return p.sphere == 0; });
                break;
            case SplitKind::Median:
            case SplitKind::Leaf: {
                mid = first + r.size() / 2;
                int axis = d.axis;
                std::nth_element(first, mid, last, [axis](const PrimRef& a, const PrimRef& b) {
                    return a.centroid2()[axis] < b.centroid2()[axis];
                });
                break;
            }
        }
        auto split = static_cast<uint32_t>(mid - refs_.data());
        if (split == r.begin || split == r.end) split = r.begin + r.size() / 2;  // safety net
        return split;
    }

    uint32_t makeLeaf(const Range& r) {
        uint32_t id = leafCount_.fetch_add(1, std::memory_order_relaxed);
        leaves_[id] = {r.begin, r.end};
        return kLeafBit | id;
    }

    struct Slot {
        Range range;
        Decision decision;
        uint32_t depth;  ///< Binary splits above this range.
    };

    /// Builds the subtree over `r`; returns a tmp node id or a leaf record ref.
    uint32_t subtree(const Range& r, uint32_t depth, uint32_t level) {
        Decision d = decide(r, depth);
        if (d.kind == SplitKind::Leaf) return makeLeaf(r);

        // Grow an 8-wide node: keep splitting the child with the largest area.
        std::array<Slot, kWidth> slots;
        slots[0] = {r, d, depth};
        uint32_t count = 1;
        while (count < kWidth) {
            int best = -1;
            float bestArea = -1;
            for (uint32_t i = 0; i < count; ++i)
                if (slots[i].decision.kind != SplitKind::Leaf &&
                    slots[i].range.bounds.area() > bestArea)
                    best = static_cast<int>(i), bestArea = slots[i].range.bounds.area();
            if (best < 0) break;
            Slot s = slots[best];
            uint32_t mid = partition(s.range, s.decision);
            Range left = makeRange(s.range.begin, mid), right = makeRange(mid, s.range.end);
            slots[best] = {left, decide(left, s.depth + 1), s.depth + 1};
            slots[count++] = {right, decide(right, s.depth + 1), s.depth + 1};
        }

        uint32_t id = nodes_.allocate();
        TmpNode& node = nodes_[id];
        node.count = count;
        uint32_t deepest = level + 1;
        for (uint32_t i = 0; i < count; ++i) {
            node.bounds[i] = slots[i].range.bounds;
            node.child[i] = kEmpty;
        }
        for (uint32_t i = 0; i < count; ++i) {
            const Slot& s = slots[i];
            if (s.decision.kind == SplitKind::Leaf) {
                node.child[i] = makeLeaf(s.range);
            } else if (pool_ && s.range.size() >= kTaskThreshold && pool_->hasIdleWorker()) {
                pool_->push([this, id, i, s, level] {
                    uint32_t c = subtree(s.range, s.depth, level + 1);
                    nodes_[id].child[i] = c;
                });
            } else {
                node.child[i] = subtree(s.range, s.depth, level + 1);
            }
        }
        uint32_t seen = maxDepth_.load(std::memory_order_relaxed);
        while (deepest > seen && !maxDepth_.compare_exchange_weak(seen, deepest)) {
        }
        return id;
    }

    std::vector<PrimRef>& refs_;
    std::vector<LeafRecord> leaves_;
    std::atomic<uint32_t> leafCount_{0};
    std::atomic<uint32_t> maxDepth_{0};
    NodePool nodes_;
    std::unique_ptr<TaskPool> pool_;
};

/// Lays the tmp tree out depth first into `out`, creating leaf blocks as they come.
class Flattener {
  public:
    Flattener(Builder& b, const std::vector<PrimRef>& refs, const Primitives& prims, BvhData& out,
              BuildSummary& summary)
        : b_(b), refs_(refs), prims_(prims), out_(out), summary_(summary) {}

    NodeRef flatten(uint32_t ref) {
        if (ref & kLeafBit) return leaf(b_.leaf(ref & ~kLeafBit));
        auto index = static_cast<uint32_t>(out_.nodes.size());
        if (index >= kLeafBit) throw std::length_error("BVH too large");
        out_.nodes.emplace_back();
        const TmpNode& tmp = b_.nodes()[ref];
        for (uint32_t i = 0; i < kWidth; ++i) {
            Node8& n = out_.nodes[index];
            bool used = i < tmp.count;
            for (int a = 0; a < 3; ++a) {
                n.lo[a][i] = used ? tmp.bounds[i].lo[a] : std::numeric_limits<float>::infinity();
                n.hi[a][i] = used ? tmp.bounds[i].hi[a] : -std::numeric_limits<float>::infinity();
            }
            n.child[i] = kEmpty;
        }
        for (uint32_t i = 0; i < tmp.count; ++i) {
            NodeRef c = flatten(tmp.child[i]);
            out_.nodes[index].child[i] = c;
        }
        return index;
    }

  private:
    NodeRef leaf(const LeafRecord& l) {
        uint32_t n = l.end - l.begin;
        summary_.leaves++;
        summary_.maxLeafSize = std::max(summary_.maxLeafSize, n);
        bool spheres = refs_[l.begin].sphere != 0;
        if (spheres) {
            auto first = static_cast<uint32_t>(out_.spheres.size());
            check(first, n);
            for (uint32_t i = l.begin; i < l.end; ++i) {
                uint32_t id = refs_[i].id;
                out_.spheres.push_back(prims_.sphereSearch(id - prims_.triangleCount()));
                out_.sphereIds.push_back(id);
            }
            return makeLeaf(true, first, n);
        }
        auto first = static_cast<uint32_t>(out_.tris.size());
        uint32_t blocks = (n + kLanes - 1) / kLanes;
        check(first, blocks);
        constexpr float nan = std::numeric_limits<float>::quiet_NaN();
        for (uint32_t b = 0; b < blocks; ++b) {
            Tri4 t;
            for (int lane = 0; lane < kLanes; ++lane) {
                uint32_t i = l.begin + b * kLanes + static_cast<uint32_t>(lane);
                bool used = i < l.end;
                const Triangle* tri = used ? &prims_.triangle(refs_[i].id) : nullptr;
                for (int c = 0; c < 3; ++c) {
                    t.v0[c][lane] = used ? tri->v0[c] : nan;
                    t.v1[c][lane] = used ? tri->v1[c] : nan;
                    t.v2[c][lane] = used ? tri->v2[c] : nan;
                }
                t.id[lane] = used ? refs_[i].id : kEmpty;
            }
            out_.tris.push_back(t);
        }
        return makeLeaf(false, first, blocks);
    }

    static void check(uint32_t first, uint32_t count) {
        if (count > kMaxLeafItems || first + count > kMaxItemIndex)
            throw std::length_error("BVH leaf data exceeds the layout's limits");
    }

    Builder& b_;
    const std::vector<PrimRef>& refs_;
    const Primitives& prims_;
    BvhData& out_;
    BuildSummary& summary_;
};

}  // namespace

BuildSummary build(const Primitives& prims, int threads, BvhData& out) {
    out = BvhData{};
    BuildSummary summary;
    uint32_t n = prims.size();
    if (n == 0) return summary;

    std::vector<PrimRef> refs(n);
    for (uint32_t i = 0; i < n; ++i) {
        Bounds3f b = prims.bounds(i);
        refs[i] = {b.lo, i, b.hi, i < prims.triangleCount() ? 0u : 1u};
    }

    Builder builder(refs, std::max(1, threads));
    uint32_t root = builder.buildAll();

    out.nodes.reserve(builder.nodes().size());
    out.tris.reserve(prims.triangleCount() / kLanes + builder.leafCount());
    Flattener flattener(builder, refs, prims, out, summary);
    out.root = flattener.flatten(root);
    summary.maxDepth = builder.maxDepth();
    out.tris.shrink_to_fit();
    return summary;
}

}  // namespace glint::bvh
