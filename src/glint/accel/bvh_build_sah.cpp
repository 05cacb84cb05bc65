#include "glint/accel/bvh_build_sah.h"

#include <array>
#include <vector>

#include "glint/core/parallel.h"

namespace glint::bvh::builder {
namespace {

constexpr uint32_t kAllAxesFrom = 32;       // smaller ranges are split along their longest axis
constexpr float kTraversalCost = 1;         // a node visit, relative to one triangle block or shape
constexpr uint32_t kMedianSplitDepth = 48;  // deeper binary splits halve by count
constexpr uint32_t kParallelBinning = 1u << 16;  // ranges this big are binned in parallel
constexpr uint32_t kBinningChunk = 1u << 14;     // refs per parallel binning chunk

struct Bin {
    Box4 bounds;
    uint32_t triangles = 0, shapes = 0;
};
using Bins = std::array<std::array<Bin, kBins>, 3>;  // the first Binning::count are used

/// Inlined: called out of line, once per range, it cost the 1M-triangle build 2.5% more
/// instructions (callgrind).
[[gnu::always_inline]] inline void binRange(const PrimRef* refs, const Binning& binning,
                                            uint32_t begin, uint32_t end, Bins& bins) {
    for (uint32_t i = begin; i < end; ++i) {
        const PrimRef& p = refs[i];
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

/// Bins all of `r`, large ranges in parallel chunks. Bins hold box unions and counts, so the
/// result does not depend on how the range was cut.
void binAll(const PrimRef* refs, const Range& r, const Binning& binning, ThreadPool& pool,
            Bins& bins) {
    if (pool.threads() == 1 || r.size() < kParallelBinning)
        return binRange(refs, binning, r.begin, r.end, bins);
    std::vector<Bins> partial((r.size() + kBinningChunk - 1) / kBinningChunk);
    parallelFor(pool, r.begin, r.end, kBinningChunk, [&](size_t first, size_t last) {
        binRange(refs, binning, static_cast<uint32_t>(first), static_cast<uint32_t>(last),
                 partial[(first - r.begin) / kBinningChunk]);
    });
    for (const Bins& p : partial)
        for (int a = 0; a < 3; ++a)
            for (int k = 0; k < binning.count; ++k) {
                bins[a][k].bounds.extend(p[a][k].bounds);
                bins[a][k].triangles += p[a][k].triangles;
                bins[a][k].shapes += p[a][k].shapes;
            }
}

}  // namespace

Decision decide(const PrimRef* refs, const Range& r, uint32_t depth, ThreadPool& pool) {
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
    binAll(refs, r, binning, pool, bins);

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

}  // namespace glint::bvh::builder
