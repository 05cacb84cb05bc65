#include "glint/accel/bvh.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <limits>

namespace glint {
namespace {

constexpr int kBins = 16;
constexpr uint32_t kMaxLeafSize = 8;  // a leaf never holds more
constexpr float kTraversalCost = 1;   // relative to one primitive test
constexpr int kMedianSplitDepth =
    Bvh::kMaxDepth - 34;  // below, halve by count: depth stays bounded

struct PrimRef {
    Bounds3f bounds;
    Vec3f centroid;
    uint32_t id;
};

struct Bin {
    Bounds3f bounds;
    uint32_t count = 0;
};

class Builder {
  public:
    Builder(std::vector<PrimRef>& refs, std::vector<BvhNode>& nodes, BvhStats& stats)
        : refs_(refs), nodes_(nodes), stats_(stats) {}

    uint32_t build(uint32_t begin, uint32_t end, uint32_t depth) {
        auto index = static_cast<uint32_t>(nodes_.size());
        nodes_.emplace_back();
        stats_.maxDepth = std::max(stats_.maxDepth, depth);

        Bounds3f bounds, centroids;
        for (uint32_t i = begin; i < end; ++i) {
            bounds.extend(refs_[i].bounds);
            centroids.extend(refs_[i].centroid);
        }
        nodes_[index].bounds = bounds;
        uint32_t n = end - begin;

        uint32_t mid = n <= 1 ? end : chooseSplit(begin, end, depth, bounds, centroids);
        if (mid == end) {
            nodes_[index].offset = begin;
            nodes_[index].count = static_cast<uint16_t>(n);
            stats_.leaves++;
            stats_.maxLeafSize = std::max(stats_.maxLeafSize, n);
            return index;
        }
        nodes_[index].axis = static_cast<uint8_t>(splitAxis_);
        build(begin, mid, depth + 1);
        uint32_t right = build(mid, end, depth + 1);
        nodes_[index].offset = right;
        return index;
    }

  private:
    /// Partitions [begin, end) and returns the split point; `end` means "make a leaf".
    uint32_t chooseSplit(uint32_t begin, uint32_t end, uint32_t depth, const Bounds3f& bounds,
                         const Bounds3f& centroids) {
        uint32_t n = end - begin;
        splitAxis_ = centroids.longestAxis();
        Vec3f extent = centroids.diagonal();
        if (depth >= kMedianSplitDepth || !(extent[splitAxis_] > 0)) return medianSplit(begin, end);

        // Binned SAH over all axes with a non-degenerate centroid extent.
        float bestCost = std::numeric_limits<float>::infinity();
        int bestAxis = -1, bestBin = 0;
        for (int axis = 0; axis < 3; ++axis) {
            if (!(extent[axis] > 0)) continue;
            std::array<Bin, kBins> bins{};
            float scale = kBins / extent[axis];
            for (uint32_t i = begin; i < end; ++i) {
                int b = binOf(refs_[i].centroid[axis], centroids.lo[axis], scale);
                bins[b].count++;
                bins[b].bounds.extend(refs_[i].bounds);
            }
            std::array<float, kBins> rightCost{};
            Bounds3f acc;
            uint32_t count = 0;
            for (int b = kBins - 1; b > 0; --b) {
                acc.extend(bins[b].bounds);
                count += bins[b].count;
                rightCost[b] = acc.area() * static_cast<float>(count);
            }
            acc = Bounds3f{};
            count = 0;
            for (int b = 0; b < kBins - 1; ++b) {
                acc.extend(bins[b].bounds);
                count += bins[b].count;
                float cost = acc.area() * static_cast<float>(count) + rightCost[b + 1];
                if (count > 0 && count < n && cost < bestCost) {
                    bestCost = cost;
                    bestAxis = axis;
                    bestBin = b;
                }
            }
        }
        if (bestAxis < 0) return medianSplit(begin, end);

        float splitCost = kTraversalCost + bestCost / bounds.area();
        if (n <= kMaxLeafSize && !(splitCost < static_cast<float>(n))) return end;

        splitAxis_ = bestAxis;
        float lo = centroids.lo[bestAxis], scale = kBins / extent[bestAxis];
        auto* first = refs_.data() + begin;
        auto* midPtr = std::partition(first, refs_.data() + end, [&](const PrimRef& r) {
            return binOf(r.centroid[bestAxis], lo, scale) <= bestBin;
        });
        auto mid = static_cast<uint32_t>(midPtr - refs_.data());
        if (mid == begin || mid == end) return medianSplit(begin, end);
        return mid;
    }

    /// Halves by count along the longest centroid axis (any order if all centroids coincide).
    uint32_t medianSplit(uint32_t begin, uint32_t end) {
        if (end - begin <= kMaxLeafSize) return end;
        uint32_t mid = begin + (end - begin) / 2;
        int axis = splitAxis_;
        std::nth_element(refs_.data() + begin, refs_.data() + mid, refs_.data() + end,
                         [axis](const PrimRef& a, const PrimRef& b) {
                             return a.centroid[axis] < b.centroid[axis];
                         });
        return mid;
    }

    static int binOf(float c, float lo, float scale) {
        int b = static_cast<int>((c - lo) * scale);
        return std::clamp(b, 0, kBins - 1);
    }

    std::vector<PrimRef>& refs_;
    std::vector<BvhNode>& nodes_;
    BvhStats& stats_;
    int splitAxis_ = 0;
};

/// Slab test against [tMin, tMax]. NaN slabs (origin on a slab plane of an axis-parallel ray)
/// are ignored, which is conservative. Far distances are widened by a few ulps so that
/// rounding never culls a box that the ray touches (flat boxes around axis-aligned triangles).
inline bool hitsBox(const Bounds3f& b, const Vec3f& o, const Vec3f& invDir, float tMin,
                    float tMax) {
    // Also widen the limit: a box entry rounded up past the best hit so far must not hide a
    // primitive whose own (strict) test would find it nearer.
    tMax *= 1 + 4 * std::numeric_limits<float>::epsilon();
    for (int a = 0; a < 3; ++a) {
        float t0 = (b.lo[a] - o[a]) * invDir[a];
        float t1 = (b.hi[a] - o[a]) * invDir[a];
        if (t0 > t1) std::swap(t0, t1);
        t1 *= 1 + 4 * std::numeric_limits<float>::epsilon();
        if (t0 > tMin) tMin = t0;
        if (t1 < tMax) tMax = t1;
        if (tMin > tMax) return false;
    }
    return true;
}

}  // namespace

void Bvh::build(const Primitives& prims, const BvhBuildOptions&) {
    auto start = std::chrono::steady_clock::now();
    prims_ = &prims;
    nodes_.clear();
    primIndex_.clear();
    stats_ = {};
    uint32_t n = prims.size();
    if (n == 0) return;

    std::vector<PrimRef> refs(n);
    for (uint32_t i = 0; i < n; ++i) {
        Bounds3f b = prims.bounds(i);
        refs[i] = {b, b.centroid(), i};
    }
    nodes_.reserve(2 * static_cast<size_t>(n));
    Builder(refs, nodes_, stats_).build(0, n, 0);
    nodes_.shrink_to_fit();

    primIndex_.resize(n);
    for (uint32_t i = 0; i < n; ++i) primIndex_[i] = refs[i].id;
    stats_.nodes = static_cast<uint32_t>(nodes_.size());
    stats_.bytes = nodes_.size() * sizeof(BvhNode) + primIndex_.size() * sizeof(uint32_t);
    stats_.buildSeconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

template <bool AnyHit>
bool Bvh::traverse(const TraversalRay& ray, Hit& hit) const {
    if (nodes_.empty()) return false;
    const Vec3f& invDir = ray.invDir;
    bool dirNeg[3] = {invDir.x < 0, invDir.y < 0, invDir.z < 0};
    uint32_t stack[kMaxDepth];
    int sp = 0;
    uint32_t node = 0;
    bool found = false;
    for (;;) {
        const BvhNode& n = nodes_[node];
        if (hitsBox(n.bounds, ray.origin, invDir, ray.tMin, std::min(ray.tMax, hit.t))) {
            if (n.count == 0) {
                // Visit the child on the near side of the split plane first.
                bool farFirst = dirNeg[n.axis];
                stack[sp++] = farFirst ? node + 1 : n.offset;
                node = farFirst ? n.offset : node + 1;
                continue;
            }
            for (uint32_t i = n.offset; i < n.offset + n.count; ++i) {
                if (prims_->intersect(primIndex_[i], ray, hit)) {
                    if constexpr (AnyHit) return true;
                    found = true;
                }
            }
        }
        if (sp == 0) break;
        node = stack[--sp];
    }
    return found;
}

bool Bvh::intersect(const TraversalRay& ray, Hit& hit) const { return traverse<false>(ray, hit); }

bool Bvh::occluded(const TraversalRay& ray) const {
    Hit hit;
    return traverse<true>(ray, hit);
}

void Bvh::intersect8(const RayPacket8& rays, HitPacket8& hits) const {
    for (int i = 0; i < 8; ++i) {
        if (!(rays.active >> i & 1)) continue;
        Ray r{{rays.ox[i], rays.oy[i], rays.oz[i]},
              {rays.dx[i], rays.dy[i], rays.dz[i]},
              rays.tMin[i],
              rays.tMax[i]};
        Hit h;
        if (intersect(TraversalRay(r), h)) hits.t[i] = h.t, hits.primId[i] = h.primId;
    }
}

const char* Bvh::isa() { return "portable"; }

}  // namespace glint
