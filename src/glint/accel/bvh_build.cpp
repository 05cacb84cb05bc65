#include "glint/accel/bvh_build.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cmath>
#include <condition_variable>
#include <functional>
#include <limits>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <thread>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace glint::bvh {
namespace {

constexpr int kBins = 16;
constexpr uint32_t kAllAxesFrom = 32;  // smaller ranges are split along their longest axis
constexpr uint32_t kMaxLeafTriangles = 2 * kLanes;
constexpr uint32_t kMaxLeafShapes = 4;
constexpr float kTraversalCost = 1;         // a node visit, relative to one triangle block or shape
constexpr uint32_t kMedianSplitDepth = 48;  // deeper binary splits halve by count
constexpr uint32_t kTaskThreshold = 8192;   // subtrees at least this big may go to idle threads
constexpr uint32_t kParallelSplit = 1u << 15;  // splits this big may run beside each other
constexpr float kInf = std::numeric_limits<float>::infinity();

/// Four floats: SSE where available, plain arrays elsewhere. Lane 3 is always 0 in boxes.
#if defined(__SSE2__)
struct V4 {
    __m128 v;
    static V4 load(const float* p) { return {_mm_and_ps(_mm_load_ps(p), xyzMask())}; }
    static V4 splat(float f) { return {_mm_set1_ps(f)}; }
    static V4 of(float x, float y, float z) { return {_mm_setr_ps(x, y, z, 0)}; }
    friend V4 min(V4 a, V4 b) { return {_mm_min_ps(a.v, b.v)}; }
    friend V4 max(V4 a, V4 b) { return {_mm_max_ps(a.v, b.v)}; }
    friend V4 operator+(V4 a, V4 b) { return {_mm_add_ps(a.v, b.v)}; }
    friend V4 operator-(V4 a, V4 b) { return {_mm_sub_ps(a.v, b.v)}; }
    friend V4 operator*(V4 a, V4 b) { return {_mm_mul_ps(a.v, b.v)}; }
    void store(float* out) const { _mm_storeu_ps(out, v); }

  private:
    static __m128 xyzMask() { return _mm_castsi128_ps(_mm_setr_epi32(-1, -1, -1, 0)); }
};
#else
struct V4 {
    float v[4];
    static V4 load(const float* p) { return {{p[0], p[1], p[2], 0}}; }
    static V4 splat(float f) { return {{f, f, f, f}}; }
    static V4 of(float x, float y, float z) { return {{x, y, z, 0}}; }
    template <typename F>
    static V4 zip(V4 a, V4 b, F f) {
        return {{f(a.v[0], b.v[0]), f(a.v[1], b.v[1]), f(a.v[2], b.v[2]), f(a.v[3], b.v[3])}};
    }
    friend V4 min(V4 a, V4 b) {
        return zip(a, b, [](float x, float y) { return y < x ? y : x; });
    }
    friend V4 max(V4 a, V4 b) {
        return zip(a, b, [](float x, float y) { return x < y ? y : x; });
    }
    friend V4 operator+(V4 a, V4 b) {
        return zip(a, b, [](float x, float y) { return x + y; });
    }
    friend V4 operator-(V4 a, V4 b) {
        return zip(a, b, [](float x, float y) { return x - y; });
    }
    friend V4 operator*(V4 a, V4 b) {
        return zip(a, b, [](float x, float y) { return x * y; });
    }
    void store(float* out) const { std::copy(v, v + 4, out); }
};
#endif

/// A box as two V4 (lane 3 unused).
struct Box4 {
    V4 lo = V4::splat(kInf), hi = V4::splat(-kInf);

    void extend(V4 l, V4 h) { lo = min(lo, l), hi = max(hi, h); }
    void extend(V4 p) { lo = min(lo, p), hi = max(hi, p); }
    void extend(const Box4& b) { lo = min(lo, b.lo), hi = max(hi, b.hi); }
    Bounds3f bounds3() const {
        alignas(16) float l[4], h[4];
        lo.store(l);
        hi.store(h);
        return {{l[0], l[1], l[2]}, {h[0], h[1], h[2]}};
    }
    /// Surface area; +inf for an empty box (never used with zero primitives).
    float area() const {
#if defined(__SSE2__)
        __m128 d = _mm_sub_ps(hi.v, lo.v);                                 // dx dy dz 0
        __m128 rot = _mm_shuffle_ps(d, d, _MM_SHUFFLE(3, 0, 2, 1));        // dy dz dx 0
        __m128 p = _mm_mul_ps(d, rot);                                     // xy yz zx 0
        __m128 s = _mm_add_ps(p, _mm_movehl_ps(p, p));                     // xy+zx yz ..
        s = _mm_add_ss(s, _mm_shuffle_ps(s, s, _MM_SHUFFLE(1, 1, 1, 1)));  // sum
        return 2 * _mm_cvtss_f32(s);
#else
        return bounds3().area();
#endif
    }
};

/// A primitive's bounds during the build; lo + hi stands for its centroid (twice it).
struct alignas(16) PrimRef {
    float lo[3];
    uint32_t id;
    float hi[3];
    uint32_t shape;  ///< 1 for shapes (spheres, boxes, ...), 0 for triangles.

    V4 lo4() const { return V4::load(lo); }
    V4 hi4() const { return V4::load(hi); }
    float centroid2(int axis) const { return lo[axis] + hi[axis]; }
};

struct Range {
    uint32_t begin = 0, end = 0, shapes = 0;
    Box4 bounds, centroids;  ///< Centroids as lo + hi.

    uint32_t size() const { return end - begin; }
    uint32_t triangles() const { return size() - shapes; }
};

/// Intersection cost of a leaf: one unit per triangle block and per shape.
float leafCost(uint32_t triangles, uint32_t shapes) {
    return static_cast<float>((triangles + kLanes - 1) / kLanes + shapes);
}

bool fitsOneLeaf(const Range& r) {
    return r.shapes == 0 ? r.size() <= kMaxLeafTriangles
                         : (r.shapes == r.size() && r.size() <= kMaxLeafShapes);
}

enum class SplitKind { Leaf, Sah, Median, Types };

struct Decision {
    SplitKind kind = SplitKind::Leaf;
    int axis = 0, bin = 0;
};

/// A child while building: a tmp node id, or a leaf: kLeafBit | the first of `size` refs.
struct ChildRef {
    uint32_t ref = kEmpty;
    uint32_t size = 0;
    bool shapes = false;  ///< A leaf of shapes (leaves hold triangles or shapes, not both).
};

/// An 8-wide node while building. Nodes are written only by the task that builds them, and
/// leaves live in their parent: building shares no counters or arrays between threads.
struct TmpNode {
    Bounds3f bounds[kWidth];
    ChildRef child[kWidth];
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
    Builder(LargeArray<PrimRef>& refs, int threads) : refs_(refs), threads_(threads) {
        if (threads > 1) pool_ = std::make_unique<TaskPool>(threads);
    }

    /// Builds the tree over all refs; returns the root.
    ChildRef buildAll() {
        Range all = makeRange(0, static_cast<uint32_t>(refs_.size()));
        rootBounds_ = all.bounds.bounds3();
        ChildRef root;
        if (pool_) {
            pool_->push([&] { root = subtree(all, 0); });
            pool_->run();
        } else {
            root = subtree(all, 0);
        }
        return root;
    }

    NodePool& nodes() { return nodes_; }
    Bounds3f rootBounds() const { return rootBounds_; }

  private:
    /// Bounds, centroid bounds and shape count of refs [begin, end).
    Range makeRange(uint32_t begin, uint32_t end) const {
        Range r;
        r.begin = begin;
        r.end = end;
        for (uint32_t i = begin; i < end; ++i) add(r, refs_[i]);
        return r;
    }

    static void add(Range& r, const PrimRef& p) {
        V4 lo = p.lo4(), hi = p.hi4();
        r.bounds.extend(lo, hi);
        r.centroids.extend(lo + hi);
        r.shapes += p.shape;
    }

    /// Where centroids fall in the bins of `r`: bin = clamp((c - lo) * scale, 0, kBins - 1),
    /// computed the same way when binning (four axes at a time) and when partitioning.
    /// Small ranges use fewer bins (one per primitive): their sweeps dominate otherwise.
    struct Binning {
        int count;
        V4 lo, scale;
        float loAxis[4], scaleAxis[4];

        explicit Binning(const Range& r)
            : count(static_cast<int>(std::clamp<uint32_t>(r.size(), 2, kBins))) {
            Bounds3f c = r.centroids.bounds3();
            Vec3f extent = c.diagonal();
            float s[3];
            for (int a = 0; a < 3; ++a) {
                // An extent of a few denormals overflows count / extent to inf, and then
                // (c - lo) * inf is NaN for the lowest centroid: treat such an axis as flat.
                float sa = extent[a] > 0 ? static_cast<float>(count) / extent[a] : 0;
                s[a] = std::isfinite(sa) ? sa : 0;
            }
            lo = V4::of(c.lo.x, c.lo.y, c.lo.z);
            scale = V4::of(s[0], s[1], s[2]);
            for (int a = 0; a < 3; ++a) loAxis[a] = c.lo[a], scaleAxis[a] = s[a];
        }
        /// Bins of a centroid on the three axes.
        void bins(V4 centroid, int* out) const {
            alignas(16) float f[4];
            min(max((centroid - lo) * scale, V4::splat(0)), V4::splat(last())).store(f);
            for (int a = 0; a < 3; ++a) out[a] = static_cast<int>(f[a]);
        }
        int bin(const PrimRef& p, int axis) const {
            float f = (p.centroid2(axis) - loAxis[axis]) * scaleAxis[axis];
            return static_cast<int>(std::min(std::max(f, 0.0f), last()));
        }
        float last() const { return static_cast<float>(count - 1); }
    };

    struct Bin {
        Box4 bounds;
        uint32_t triangles = 0, shapes = 0;
    };
    using Bins = std::array<std::array<Bin, kBins>, 3>;  // the first Binning::count are used

    void binRange(const Binning& binning, uint32_t begin, uint32_t end, Bins& bins) const {
        for (uint32_t i = begin; i < end; ++i) {
            const PrimRef& p = refs_[i];
            V4 lo = p.lo4(), hi = p.hi4();
            int b[3];
            binning.bins(lo + hi, b);
            for (int a = 0; a < 3; ++a) {
                Bin& bin = bins[a][b[a]];
                bin.bounds.extend(lo, hi);
                bin.triangles += 1 - p.shape;
                bin.shapes += p.shape;
            }
        }
    }

    /// Bins all of `r`, in parallel chunks when it is large and threads are idle.
    void binAll(const Range& r, const Binning& binning, Bins& bins) const {
        constexpr uint32_t kParallelBinning = 1u << 16;
        int threads =
            pool_ && r.size() >= kParallelBinning && pool_->hasIdleWorker() ? threads_ : 1;
        if (threads == 1) return binRange(binning, r.begin, r.end, bins);
        std::vector<Bins> partial(static_cast<size_t>(threads));
        std::vector<std::thread> workers;
        uint32_t chunk =
            (r.size() + static_cast<uint32_t>(threads) - 1) / static_cast<uint32_t>(threads);
        for (int t = 0; t < threads; ++t) {
            uint32_t b = r.begin + static_cast<uint32_t>(t) * chunk;
            uint32_t e = std::min(r.end, b + chunk);
            if (t + 1 < threads)
                workers.emplace_back([&, b, e, t] { binRange(binning, b, e, partial[t]); });
            else
                binRange(binning, b, e, partial[t]);
        }
        for (auto& w : workers) w.join();
        for (const Bins& p : partial)
            for (int a = 0; a < 3; ++a)
                for (int k = 0; k < binning.count; ++k) {
                    bins[a][k].bounds.extend(p[a][k].bounds);
                    bins[a][k].triangles += p[a][k].triangles;
                    bins[a][k].shapes += p[a][k].shapes;
                }
    }

    /// Leaf, or how to split: binned SAH over the three axes, else halving by count.
    Decision decide(const Range& r, uint32_t depth) const {
        uint32_t n = r.size();
        // One block of triangles: any split costs a node visit plus two blocks' worth of area.
        if (n <= 1 || (r.shapes == 0 && n <= kLanes)) return {};
        bool mixed = r.shapes != 0 && r.shapes != n;
        Bounds3f centroids = r.centroids.bounds3();
        if (depth >= kMedianSplitDepth) {
            if (fitsOneLeaf(r)) return {};
            return {mixed ? SplitKind::Types : SplitKind::Median, centroids.longestAxis(), 0};
        }

        Binning binning(r);
        const int nb = binning.count;
        Bins bins;
        for (int a = 0; a < 3; ++a) std::fill_n(bins[a].begin(), nb, Bin{});
        binAll(r, binning, bins);

        Vec3f extent = centroids.diagonal();
        float bestCost = kInf;
        int bestAxis = -1, bestBin = 0;
        // Small ranges: only the longest axis (the sweeps cost more than the binning there).
        const int longest = centroids.longestAxis();
        for (int a = 0; a < 3; ++a) {
            if (!(extent[a] > 0) || (n < kAllAxesFrom && a != longest)) continue;
            std::array<float, kBins> right{};
            Box4 acc;
            uint32_t tris = 0, shp = 0;
            for (int b = nb - 1; b > 0; --b) {
                acc.extend(bins[a][b].bounds);
                tris += bins[a][b].triangles;
                shp += bins[a][b].shapes;
                right[b] = tris + shp ? acc.area() * leafCost(tris, shp) : 0;
            }
            acc = {};
            tris = shp = 0;
            for (int b = 0; b < nb - 1; ++b) {
                acc.extend(bins[a][b].bounds);
                tris += bins[a][b].triangles;
                shp += bins[a][b].shapes;
                uint32_t left = tris + shp;
                if (left == 0 || left == n) continue;
                float cost = acc.area() * leafCost(tris, shp) + right[b + 1];
                if (cost < bestCost) bestCost = cost, bestAxis = a, bestBin = b;
            }
        }

        float area = r.bounds.area();
        float splitCost = bestAxis < 0 ? kInf : kTraversalCost + bestCost / area;
        if (fitsOneLeaf(r) && !(splitCost < leafCost(r.triangles(), r.shapes))) return {};
        if (bestAxis >= 0) return {SplitKind::Sah, bestAxis, bestBin};
        // All centroids coincide (or the areas are degenerate): halve, separating types first.
        if (mixed) return {SplitKind::Types, 0, 0};
        if (fitsOneLeaf(r)) return {};
        return {SplitKind::Median, centroids.longestAxis(), 0};
    }

    /// Moves the refs of `r` for which `left` holds to the front, computing both sides' ranges
    /// on the way (no second pass over the data).
    template <typename Pred>
    std::pair<Range, Range> partitionBy(const Range& r, Pred left) {
        Range L, R;
        uint32_t i = r.begin, j = r.end;
        for (;;) {
            while (i < j && left(refs_[i])) add(L, refs_[i++]);
            while (i < j && !left(refs_[j - 1])) add(R, refs_[--j]);
            if (i >= j) break;
            std::swap(refs_[i], refs_[j - 1]);
            add(L, refs_[i++]);
            add(R, refs_[--j]);
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

    /// Builds the subtree over `r`.
    ChildRef subtree(const Range& r, uint32_t depth) {
        Decision d = decide(r, depth);
        if (d.kind == SplitKind::Leaf) return makeLeaf(r);

        // Grow an 8-wide node in rounds: each round splits, largest area first, as many of the
        // splittable children as still fit. The splits of a round are independent, so large
        // ones run in parallel; the rule does not depend on the thread count.
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
            std::vector<std::thread> helpers;
            for (uint32_t j = 0; j < take; ++j) {
                bool big = slots[order[j]].range.size() >= kParallelSplit;
                if (j + 1 < take && big && pool_ && pool_->hasIdleWorker())
                    helpers.emplace_back(splitOne, j);
                else
                    splitOne(j);
            }
            for (auto& h : helpers) h.join();
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
            } else if (pool_ && s.range.size() >= kTaskThreshold) {
                // Every large subtree is a task, whichever thread is free takes it: a split
                // handed out only to idle threads left them waiting while one thread built
                // most of the tree.
                pool_->push([this, id, i, s] { nodes_[id].child[i] = subtree(s.range, s.depth); });
            } else {
                node.child[i] = subtree(s.range, s.depth);
            }
        }
        return {id, 0};
    }

    LargeArray<PrimRef>& refs_;
    Bounds3f rootBounds_;
    NodePool nodes_;
    int threads_;
    std::unique_ptr<TaskPool> pool_;
};

/// Sizes of a laid-out subtree, and a place to write one.
struct Layout {
    uint32_t nodes = 0, tris = 0, shapes = 0, runs = 0;

    Layout& operator+=(const Layout& o) {
        nodes += o.nodes, tris += o.tris, shapes += o.shapes, runs += o.runs;
        return *this;
    }
};

/// Lays the tmp tree out depth first into `out`, creating leaf blocks as they come. Subtrees
/// can be laid out concurrently: each writes at positions computed beforehand, so the layout
/// is the same as a single depth-first pass.
class Flattener {
  public:
    Flattener(Builder& b, const LargeArray<PrimRef>& refs, const Primitives& prims, BvhData& out)
        : b_(b), refs_(refs), prims_(prims), out_(out) {}

    /// What `c` occupies once laid out.
    Layout size(const ChildRef& c) {
        if (c.ref & kLeafBit) {
            if (!c.shapes) return Layout{0, (c.size + kLanes - 1) / kLanes, 0, 0};
            return Layout{0, 0, c.size, spheresOnly(c) ? 0u : 1u};
        }
        Layout l{1, 0, 0, 0};
        const TmpNode& tmp = b_.nodes()[c.ref];
        for (uint32_t i = 0; i < tmp.count; ++i) l += size(tmp.child[i]);
        return l;
    }

    /// Lays out `c`, `depth` levels of nodes below the root, starting at `at` (which advances);
    /// returns its final reference.
    NodeRef flatten(const ChildRef& c, Layout& at, uint32_t depth, BuildSummary& summary) {
        if (c.ref & kLeafBit) return leaf(c, at, summary);
        summary.maxDepth = std::max(summary.maxDepth, depth + 1);
        uint32_t index = at.nodes++;
        if (index >= kLeafBit) throw std::length_error("BVH too large");
        const TmpNode& tmp = b_.nodes()[c.ref];
        writeNode(index, tmp);
        for (uint32_t i = 0; i < tmp.count; ++i)
            out_.nodes[index].child[i] = flatten(tmp.child[i], at, depth + 1, summary);
        return index;
    }

    /// Lays out the whole tree, the root's subtrees on up to `threads` threads.
    NodeRef flattenAll(const ChildRef& root, int threads, BuildSummary& summary) {
        Layout total = size(root);
        out_.nodes.resize(total.nodes);
        out_.tris.resize(total.tris);
        out_.shapes.resize(total.shapes);
        out_.shapeIds.resize(total.shapes);
        out_.shapeRuns.resize(total.runs);
        Layout at;
        if ((root.ref & kLeafBit) || threads <= 1) return flatten(root, at, 0, summary);

        const TmpNode& tmp = b_.nodes()[root.ref];
        summary.maxDepth = 1;
        writeNode(at.nodes++, tmp);
        std::array<Layout, kWidth> starts;
        std::array<BuildSummary, kWidth> parts{};
        for (uint32_t i = 0; i < tmp.count; ++i) {
            starts[i] = at;
            at += size(tmp.child[i]);
        }
        std::atomic<uint32_t> next{0};
        auto work = [&] {
            for (uint32_t i; (i = next.fetch_add(1)) < tmp.count;)
                out_.nodes[0].child[i] = flatten(tmp.child[i], starts[i], 1, parts[i]);
        };
        std::vector<std::thread> helpers;
        for (int t = 1; t < std::min<int>(threads, static_cast<int>(tmp.count)); ++t)
            helpers.emplace_back(work);
        work();
        for (auto& h : helpers) h.join();
        for (uint32_t i = 0; i < tmp.count; ++i) {
            summary.leaves += parts[i].leaves;
            summary.maxDepth = std::max(summary.maxDepth, parts[i].maxDepth);
            summary.maxLeafSize = std::max(summary.maxLeafSize, parts[i].maxLeafSize);
        }
        return 0;
    }

  private:
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

    Builder& b_;
    const LargeArray<PrimRef>& refs_;
    const Primitives& prims_;
    BvhData& out_;
};

}  // namespace

BuildSummary build(const Primitives& prims, int threads, BvhData& out) {
    out = BvhData{};
    BuildSummary summary;
    uint32_t n = prims.boundedCount();  // planes are not in the tree (Bvh keeps them)
    if (n == 0) return summary;

    LargeArray<PrimRef> refs(n);
    for (uint32_t i = 0; i < n; ++i) {
        Bounds3f b = prims.bounds(i);
        refs[i] = {{b.lo.x, b.lo.y, b.lo.z},
                   i,
                   {b.hi.x, b.hi.y, b.hi.z},
                   i < prims.triangleCount() ? 0u : 1u};
    }

    Builder builder(refs, std::max(1, threads));
    ChildRef root = builder.buildAll();
    summary.bounds = builder.rootBounds();

    Flattener flattener(builder, refs, prims, out);
    out.root = flattener.flattenAll(root, std::max(1, threads), summary);

    return summary;
}

}  // namespace glint::bvh
