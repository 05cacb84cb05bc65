#pragma once
/// How the BVH builder decides what to do with a range of refs: make it a leaf, or split it
/// where the binned surface area heuristic says (else halve it by count). Internal to the
/// builder (bvh_build*.cpp).

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "glint/accel/bvh_build_refs.h"
#include "glint/accel/bvh_layout.h"

namespace glint {
class ThreadPool;
}

namespace glint::bvh::builder {

constexpr int kBins = 16;
constexpr uint32_t kMaxLeafTriangles = 2 * kLanes;
constexpr uint32_t kMaxLeafShapes = 4;

/// Intersection cost of a leaf: one unit per triangle block and per shape.
inline float leafCost(uint32_t triangles, uint32_t shapes) {
    return static_cast<float>((triangles + kLanes - 1) / kLanes + shapes);
}

/// Whether `r` may be one leaf: leaves hold triangles or shapes, not both.
inline bool fitsOneLeaf(const Range& r) {
    return r.shapes == 0 ? r.size() <= kMaxLeafTriangles
                         : (r.shapes == r.size() && r.size() <= kMaxLeafShapes);
}

/// Where centroids fall in the bins of a range: bin = clamp((c - lo) * scale, 0, count - 1),
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

enum class SplitKind { Leaf, Sah, Median, Types };

struct Decision {
    SplitKind kind = SplitKind::Leaf;
    int axis = 0, bin = 0;  ///< Sah: refs in bins <= bin on `axis` go left. Median: the axis.
};

/// Leaf, or how to split `r` (refs[r.begin, r.end)), `depth` binary splits below the root:
/// binned SAH over the three axes, else halving by count; below a depth bound always halving.
/// Large ranges are binned on `pool`'s threads. The answer does not depend on the threads.
Decision decide(const PrimRef* refs, const Range& r, uint32_t depth, ThreadPool& pool);

}  // namespace glint::bvh::builder
