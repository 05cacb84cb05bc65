// The WebAssembly SIMD128 traversal kernels (the web build, which is always compiled with
// -msimd128): the AVX2 set's structure on 4-wide vectors. Node boxes are tested as two halves
// of four children, triangles four at a time, packets as two halves of four rays.
//
// Bit for bit the portable kernels: the same operations in the same order (no FMA: wasm has
// none without relaxed SIMD, and -ffp-contract=off), and min/max as std::min/std::max do them
// through the pseudo-minimum and pseudo-maximum instructions: pmin(a, b) = b < a ? b : a is
// std::min(a, b), pmax(a, b) = a < b ? b : a is std::max(a, b), NaN included. (They are also
// the fast ones: f32x4.min and .max propagate NaN, which engines pay for with extra
// instructions on x86.)

#include <wasm_simd128.h>

#include <algorithm>
#include <bit>
#include <limits>

#include "glint/accel/bvh_build.h"
#include "glint/accel/bvh_kernels.h"
#include "glint/accel/bvh_packet.h"
#include "glint/geometry/shapes.h"
#include "glint/geometry/sphere.h"
#include "glint/geometry/triangle.h"

namespace glint::bvh::simd128 {
namespace {

struct Isa {
    struct RayBoxes {
        v128_t origin[3], invDir[3], tMin;
        /// Float offsets in a Node8 of the planes a ray meets first and last on each axis
        /// (`hi` first where it runs towards -axis).
        int nearOff[3], farOff[3];

        explicit RayBoxes(const TraversalRay& r) {
            for (int a = 0; a < 3; ++a) {
                origin[a] = wasm_f32x4_splat(r.origin[a]);
                invDir[a] = wasm_f32x4_splat(r.invDir[a]);
                bool neg = r.invDir[a] < 0;
                nearOff[a] = (neg ? 3 + a : a) * kWidth;
                farOff[a] = (neg ? a : 3 + a) * kWidth;
            }
            tMin = wasm_f32x4_splat(r.tMin);
        }
    };

    /// Children [h, h + 4) of the node at `base` (lo[3][8] then hi[3][8]).
    static uint32_t boxHalf(const float* base, int h, const RayBoxes& r, v128_t tMax,
                            float* tNear) {
        const v128_t farScale = wasm_f32x4_splat(1 + 4 * std::numeric_limits<float>::epsilon());
        v128_t enter = r.tMin, exit = wasm_f32x4_splat(std::numeric_limits<float>::infinity());
        for (int a = 0; a < 3; ++a) {
            v128_t tn = wasm_f32x4_mul(
                wasm_f32x4_sub(wasm_v128_load(base + r.nearOff[a] + h), r.origin[a]), r.invDir[a]);
            v128_t tf = wasm_f32x4_mul(
                wasm_f32x4_sub(wasm_v128_load(base + r.farOff[a] + h), r.origin[a]), r.invDir[a]);
            enter = wasm_f32x4_pmax(enter, tn);
            exit = wasm_f32x4_pmin(exit, tf);
        }
        exit = wasm_f32x4_pmin(wasm_f32x4_mul(exit, farScale), tMax);
        wasm_v128_store(tNear + h, enter);
        return wasm_i32x4_bitmask(wasm_f32x4_le(enter, exit));
    }

    static uint32_t boxes(const Node8& n, const RayBoxes& r, float tMax, float* tNear) {
        const v128_t tm = wasm_f32x4_splat(tMax);
        return boxHalf(n.lo[0], 0, r, tm, tNear) | boxHalf(n.lo[0], 4, r, tm, tNear) << 4;
    }

    /// The watertight test after the shear, on four lanes (intersectTriangle()'s operations in
    /// its order): the lanes whose edge functions share a sign and sum to nonzero, and their t,
    /// not yet checked against any interval.
    static v128_t edges(v128_t ax, v128_t ay, v128_t az, v128_t bx, v128_t by, v128_t bz, v128_t cx,
                        v128_t cy, v128_t cz, v128_t sz, v128_t& t) {
        v128_t u = wasm_f32x4_sub(wasm_f32x4_mul(cx, by), wasm_f32x4_mul(cy, bx));
        v128_t v = wasm_f32x4_sub(wasm_f32x4_mul(ax, cy), wasm_f32x4_mul(ay, cx));
        v128_t w = wasm_f32x4_sub(wasm_f32x4_mul(bx, ay), wasm_f32x4_mul(by, ax));
        const v128_t zero = wasm_f32x4_splat(0);
        v128_t anyNeg = wasm_v128_or(wasm_v128_or(wasm_f32x4_lt(u, zero), wasm_f32x4_lt(v, zero)),
                                     wasm_f32x4_lt(w, zero));
        v128_t anyPos = wasm_v128_or(wasm_v128_or(wasm_f32x4_gt(u, zero), wasm_f32x4_gt(v, zero)),
                                     wasm_f32x4_gt(w, zero));
        v128_t det = wasm_f32x4_add(wasm_f32x4_add(u, v), w);
        v128_t tScaled = wasm_f32x4_add(wasm_f32x4_add(wasm_f32x4_mul(u, wasm_f32x4_mul(sz, az)),
                                                       wasm_f32x4_mul(v, wasm_f32x4_mul(sz, bz))),
                                        wasm_f32x4_mul(w, wasm_f32x4_mul(sz, cz)));
        t = wasm_f32x4_div(tScaled, det);
        // andnot(a, b) is a & ~b.
        return wasm_v128_andnot(wasm_f32x4_ne(det, zero), wasm_v128_and(anyNeg, anyPos));
    }

    static uint32_t triangles(const Tri4& b, const TraversalRay& ray, float tBest, float* t) {
        // The operations of intersectTriangle(), in the same order, four lanes at a time.
        const int kx = ray.kx, ky = ray.ky, kz = ray.kz;
        const v128_t ox = wasm_f32x4_splat(ray.origin[kx]), oy = wasm_f32x4_splat(ray.origin[ky]),
                     oz = wasm_f32x4_splat(ray.origin[kz]);
        const v128_t sx = wasm_f32x4_splat(ray.sx), sy = wasm_f32x4_splat(ray.sy),
                     sz = wasm_f32x4_splat(ray.sz);
        auto shear = [&](const float(&v)[3][kLanes], v128_t& x, v128_t& y, v128_t& z) {
            v128_t px = wasm_f32x4_sub(wasm_v128_load(v[kx]), ox);
            v128_t py = wasm_f32x4_sub(wasm_v128_load(v[ky]), oy);
            z = wasm_f32x4_sub(wasm_v128_load(v[kz]), oz);
            x = wasm_f32x4_sub(px, wasm_f32x4_mul(sx, z));
            y = wasm_f32x4_sub(py, wasm_f32x4_mul(sy, z));
        };
        v128_t ax, ay, az, bx, by, bz, cx, cy, cz;
        shear(b.v0, ax, ay, az);
        shear(b.v1, bx, by, bz);
        shear(b.v2, cx, cy, cz);
        v128_t tHit;
        v128_t ok = edges(ax, ay, az, bx, by, bz, cx, cy, cz, sz, tHit);
        ok = wasm_v128_and(ok, wasm_f32x4_gt(tHit, wasm_f32x4_splat(ray.tMin)));
        ok = wasm_v128_and(ok, wasm_f32x4_lt(tHit, wasm_f32x4_splat(ray.tMax)));
        ok = wasm_v128_and(ok, wasm_f32x4_le(tHit, wasm_f32x4_splat(tBest)));
        wasm_v128_store(t, tHit);
        return wasm_i32x4_bitmask(ok);
    }

    // Packets (see bvh_traverse.inl).
    struct PacketBoxes {
        v128_t originNear[3], originFar[3], invLo[3], invHi[3], tMin;
        int nearHi[3];

        explicit PacketBoxes(const Packet& p) {
            for (int a = 0; a < 3; ++a) {
                originNear[a] = wasm_f32x4_splat(p.originNear[a]);
                originFar[a] = wasm_f32x4_splat(p.originFar[a]);
                invLo[a] = wasm_f32x4_splat(p.invLo[a]);
                invHi[a] = wasm_f32x4_splat(p.invHi[a]);
                nearHi[a] = p.nearHi[a];
            }
            tMin = wasm_f32x4_splat(p.tMin);
        }
    };

    /// Per-lane data for the watertight test of one triangle against eight rays (two halves of
    /// four) sharing the test's axes (kx, ky, kz). Inactive lanes get tMin = +inf: they never
    /// accept a hit.
    struct PacketLanes {
        int kx = 0, ky = 1, kz = 2;
        v128_t ox[2], oy[2], oz[2], sx[2], sy[2], sz[2], tMin[2], tMax[2];

        explicit PacketLanes(const Packet& p) {
            alignas(16) float v[8][8];
            for (int i = 0; i < 8; ++i) {
                const TraversalRay& r = p.rays[i];
                bool on = p.active >> i & 1;
                if (on) kx = r.kx, ky = r.ky, kz = r.kz;
                v[0][i] = r.origin[r.kx], v[1][i] = r.origin[r.ky], v[2][i] = r.origin[r.kz];
                v[3][i] = r.sx, v[4][i] = r.sy, v[5][i] = r.sz;
                v[6][i] = on ? r.tMin : std::numeric_limits<float>::infinity();
                v[7][i] = r.tMax;
            }
            v128_t* out[8] = {ox, oy, oz, sx, sy, sz, tMin, tMax};
            for (int k = 0; k < 8; ++k)
                for (int h = 0; h < 2; ++h) out[k][h] = wasm_v128_load(v[k] + 4 * h);
        }
    };

    static uint32_t packetBoxHalf(const Node8& n, int h, const PacketBoxes& b, v128_t tMax,
                                  float* tNear) {
        const v128_t farScale = wasm_f32x4_splat(1 + 4 * std::numeric_limits<float>::epsilon());
        v128_t enter = b.tMin, exit = wasm_f32x4_splat(std::numeric_limits<float>::infinity());
        for (int a = 0; a < 3; ++a) {
            v128_t dn = wasm_f32x4_sub(wasm_v128_load((b.nearHi[a] ? n.hi[a] : n.lo[a]) + h),
                                       b.originNear[a]);
            v128_t df = wasm_f32x4_sub(wasm_v128_load((b.nearHi[a] ? n.lo[a] : n.hi[a]) + h),
                                       b.originFar[a]);
            enter = wasm_f32x4_pmax(enter, wasm_f32x4_pmin(wasm_f32x4_mul(dn, b.invLo[a]),
                                                           wasm_f32x4_mul(dn, b.invHi[a])));
            exit = wasm_f32x4_pmin(exit, wasm_f32x4_pmax(wasm_f32x4_mul(df, b.invLo[a]),
                                                         wasm_f32x4_mul(df, b.invHi[a])));
        }
        exit = wasm_f32x4_pmin(wasm_f32x4_mul(exit, farScale), tMax);
        wasm_v128_store(tNear + h, enter);
        return wasm_i32x4_bitmask(wasm_f32x4_le(enter, exit));
    }

    static uint32_t packetBoxes(const Node8& n, const PacketBoxes& b, float tMax, float* tNear) {
        const v128_t tm = wasm_f32x4_splat(tMax);
        return packetBoxHalf(n, 0, b, tm, tNear) | packetBoxHalf(n, 4, b, tm, tNear) << 4;
    }

    /// Triangle k of `b` against rays [4h, 4h + 4): intersectTriangle()'s arithmetic per lane.
    /// Returns the lanes hit within their range; `t` receives the distances.
    static v128_t laneHits(const Tri4& b, int k, const PacketLanes& l, int h, v128_t& t) {
        const int kx = l.kx, ky = l.ky, kz = l.kz;
        auto shear = [&](const float(&v)[3][kLanes], v128_t& x, v128_t& y, v128_t& z) {
            v128_t px = wasm_f32x4_sub(wasm_f32x4_splat(v[kx][k]), l.ox[h]);
            v128_t py = wasm_f32x4_sub(wasm_f32x4_splat(v[ky][k]), l.oy[h]);
            z = wasm_f32x4_sub(wasm_f32x4_splat(v[kz][k]), l.oz[h]);
            x = wasm_f32x4_sub(px, wasm_f32x4_mul(l.sx[h], z));
            y = wasm_f32x4_sub(py, wasm_f32x4_mul(l.sy[h], z));
        };
        v128_t ax, ay, az, bx, by, bz, cx, cy, cz;
        shear(b.v0, ax, ay, az);
        shear(b.v1, bx, by, bz);
        shear(b.v2, cx, cy, cz);
        v128_t ok = edges(ax, ay, az, bx, by, bz, cx, cy, cz, l.sz[h], t);
        ok = wasm_v128_and(ok, wasm_f32x4_gt(t, l.tMin[h]));
        return wasm_v128_and(ok, wasm_f32x4_lt(t, l.tMax[h]));
    }

    /// The four triangles of `b` against the eight rays; each lane keeps its best hit by the
    /// closerHit rule.
    static void packetTriangles(const Tri4& b, const PacketLanes& l, float* bestT,
                                uint32_t* bestId) {
        for (int h = 0; h < 2; ++h) {
            v128_t bt = wasm_v128_load(bestT + 4 * h);
            v128_t bid = wasm_v128_load(bestId + 4 * h);
            for (int k = 0; k < kLanes; ++k) {
                if (b.id[k] == kEmpty) continue;
                v128_t t;
                v128_t ok = laneHits(b, k, l, h, t);
                v128_t id = wasm_i32x4_splat(static_cast<int>(b.id[k]));
                v128_t better =
                    wasm_v128_or(wasm_f32x4_lt(t, bt),
                                 wasm_v128_and(wasm_f32x4_eq(t, bt), wasm_u32x4_gt(bid, id)));
                v128_t take = wasm_v128_and(ok, better);
                bt = wasm_v128_bitselect(t, bt, take);
                bid = wasm_v128_bitselect(id, bid, take);
            }
            wasm_v128_store(bestT + 4 * h, bt);
            wasm_v128_store(bestId + 4 * h, bid);
        }
    }
};

#include "glint/accel/bvh_traverse.inl"

}  // namespace

bool intersect(const BvhData& d, const TraversalRay& ray, Hit& hit) {
    return traverse<false>(d, ray, hit);
}

bool occluded(const BvhData& d, const TraversalRay& ray) {
    Hit hit;
    return traverse<true>(d, ray, hit);
}

void intersect8(const BvhData& d, const RayPacket8& rays, HitPacket8& hits) {
    traversePacket(d, rays, hits);
}

}  // namespace glint::bvh::simd128
