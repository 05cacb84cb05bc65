// The AVX2 traversal kernels. Every header is included first, for the baseline instruction set;
// only the code below the target pragma, in its own namespace, may use AVX2. So no inline
// function shared with other files is ever compiled with AVX2 (which could leak AVX2
// instructions into the portable path through the linker's choice of one copy).

#include <immintrin.h>

#include <algorithm>
#include <bit>
#include <limits>

#include "glint/accel/bvh_build.h"
#include "glint/accel/bvh_kernels.h"
#include "glint/accel/bvh_packet.h"
#include "glint/geometry/shapes.h"
#include "glint/geometry/sphere.h"
#include "glint/geometry/triangle.h"

#pragma GCC push_options
#pragma GCC target("avx2")

namespace glint::bvh::avx2 {
namespace {

struct Isa {
    struct RayBoxes {
        __m256 origin[3], invDir[3], tMin;
        /// Float offsets in a Node8 of the planes a ray meets first and last on each axis
        /// (`hi` first where it runs towards -axis).
        int nearOff[3], farOff[3];

        explicit RayBoxes(const TraversalRay& r) {
            for (int a = 0; a < 3; ++a) {
                origin[a] = _mm256_set1_ps(r.origin[a]);
                invDir[a] = _mm256_set1_ps(r.invDir[a]);
                bool neg = r.invDir[a] < 0;
                nearOff[a] = (neg ? 3 + a : a) * kWidth;
                farOff[a] = (neg ? a : 3 + a) * kWidth;
            }
            tMin = _mm256_set1_ps(r.tMin);
        }
    };

    static uint32_t boxes(const Node8& n, const RayBoxes& r, float tMax, float* tNear) {
        const __m256 farScale = _mm256_set1_ps(1 + 4 * std::numeric_limits<float>::epsilon());
        __m256 enter = r.tMin, exit = _mm256_set1_ps(std::numeric_limits<float>::infinity());
        const float* base = n.lo[0];  // lo[3][8] then hi[3][8]
        for (int a = 0; a < 3; ++a) {
            __m256 tn = _mm256_mul_ps(
                _mm256_sub_ps(_mm256_load_ps(base + r.nearOff[a]), r.origin[a]), r.invDir[a]);
            __m256 tf = _mm256_mul_ps(
                _mm256_sub_ps(_mm256_load_ps(base + r.farOff[a]), r.origin[a]), r.invDir[a]);
            enter = _mm256_max_ps(enter, tn);
            exit = _mm256_min_ps(exit, tf);
        }
        exit = _mm256_min_ps(_mm256_mul_ps(exit, farScale), _mm256_set1_ps(tMax));
        _mm256_store_ps(tNear, enter);
        return static_cast<uint32_t>(_mm256_movemask_ps(_mm256_cmp_ps(enter, exit, _CMP_LE_OQ)));
    }

    static uint32_t triangles(const Tri4& b, const TraversalRay& ray, float tBest, float* t) {
        // The operations of intersectTriangle(), in the same order, four lanes at a time.
        const int kx = ray.kx, ky = ray.ky, kz = ray.kz;
        const __m128 ox = _mm_set1_ps(ray.origin[kx]), oy = _mm_set1_ps(ray.origin[ky]),
                     oz = _mm_set1_ps(ray.origin[kz]);
        const __m128 sx = _mm_set1_ps(ray.sx), sy = _mm_set1_ps(ray.sy), sz = _mm_set1_ps(ray.sz);
        auto shear = [&](const float(&v)[3][kLanes], __m128& x, __m128& y, __m128& z) {
            __m128 px = _mm_sub_ps(_mm_load_ps(v[kx]), ox);
            __m128 py = _mm_sub_ps(_mm_load_ps(v[ky]), oy);
            z = _mm_sub_ps(_mm_load_ps(v[kz]), oz);
            x = _mm_sub_ps(px, _mm_mul_ps(sx, z));
            y = _mm_sub_ps(py, _mm_mul_ps(sy, z));
        };
        __m128 ax, ay, az, bx, by, bz, cx, cy, cz;
        shear(b.v0, ax, ay, az);
        shear(b.v1, bx, by, bz);
        shear(b.v2, cx, cy, cz);
        __m128 u = _mm_sub_ps(_mm_mul_ps(cx, by), _mm_mul_ps(cy, bx));
        __m128 v = _mm_sub_ps(_mm_mul_ps(ax, cy), _mm_mul_ps(ay, cx));
        __m128 w = _mm_sub_ps(_mm_mul_ps(bx, ay), _mm_mul_ps(by, ax));
        const __m128 zero = _mm_setzero_ps();
        __m128 anyNeg = _mm_or_ps(_mm_or_ps(_mm_cmplt_ps(u, zero), _mm_cmplt_ps(v, zero)),
                                  _mm_cmplt_ps(w, zero));
        __m128 anyPos = _mm_or_ps(_mm_or_ps(_mm_cmpgt_ps(u, zero), _mm_cmpgt_ps(v, zero)),
                                  _mm_cmpgt_ps(w, zero));
        __m128 det = _mm_add_ps(_mm_add_ps(u, v), w);
        __m128 tScaled = _mm_add_ps(
            _mm_add_ps(_mm_mul_ps(u, _mm_mul_ps(sz, az)), _mm_mul_ps(v, _mm_mul_ps(sz, bz))),
            _mm_mul_ps(w, _mm_mul_ps(sz, cz)));
        __m128 tHit = _mm_div_ps(tScaled, det);
        __m128 ok = _mm_andnot_ps(_mm_and_ps(anyNeg, anyPos), _mm_cmpneq_ps(det, zero));
        ok = _mm_and_ps(ok, _mm_cmpgt_ps(tHit, _mm_set1_ps(ray.tMin)));
        ok = _mm_and_ps(ok, _mm_cmplt_ps(tHit, _mm_set1_ps(ray.tMax)));
        ok = _mm_and_ps(ok, _mm_cmple_ps(tHit, _mm_set1_ps(tBest)));
        _mm_store_ps(t, tHit);
        return static_cast<uint32_t>(_mm_movemask_ps(ok));
    }

    // Packets (see bvh_traverse.inl).
    struct PacketBoxes {
        __m256 originNear[3], originFar[3], invLo[3], invHi[3], tMin;
        int nearHi[3];

        explicit PacketBoxes(const Packet& p) {
            for (int a = 0; a < 3; ++a) {
                originNear[a] = _mm256_set1_ps(p.originNear[a]);
                originFar[a] = _mm256_set1_ps(p.originFar[a]);
                invLo[a] = _mm256_set1_ps(p.invLo[a]);
                invHi[a] = _mm256_set1_ps(p.invHi[a]);
                nearHi[a] = p.nearHi[a];
            }
            tMin = _mm256_set1_ps(p.tMin);
        }
    };

    /// Per-lane data for the watertight test of one triangle against eight rays sharing the
    /// test's axes (kx, ky, kz). Inactive lanes get tMin = +inf: they never accept a hit.
    struct PacketLanes {
        int kx = 0, ky = 1, kz = 2;
        __m256 ox, oy, oz, sx, sy, sz, tMin, tMax;

        explicit PacketLanes(const Packet& p) {
            alignas(32) float v[8][8];
            for (int i = 0; i < 8; ++i) {
                const TraversalRay& r = p.rays[i];
                bool on = p.active >> i & 1;
                if (on) kx = r.kx, ky = r.ky, kz = r.kz;
                v[0][i] = r.origin[r.kx], v[1][i] = r.origin[r.ky], v[2][i] = r.origin[r.kz];
                v[3][i] = r.sx, v[4][i] = r.sy, v[5][i] = r.sz;
                v[6][i] = on ? r.tMin : std::numeric_limits<float>::infinity();
                v[7][i] = r.tMax;
            }
            __m256* out[8] = {&ox, &oy, &oz, &sx, &sy, &sz, &tMin, &tMax};
            for (int k = 0; k < 8; ++k) *out[k] = _mm256_load_ps(v[k]);
        }
    };

    static uint32_t packetBoxes(const Node8& n, const PacketBoxes& b, float tMax, float* tNear) {
        const __m256 farScale = _mm256_set1_ps(1 + 4 * std::numeric_limits<float>::epsilon());
        __m256 enter = b.tMin, exit = _mm256_set1_ps(std::numeric_limits<float>::infinity());
        for (int a = 0; a < 3; ++a) {
            __m256 dn =
                _mm256_sub_ps(_mm256_load_ps(b.nearHi[a] ? n.hi[a] : n.lo[a]), b.originNear[a]);
            __m256 df =
                _mm256_sub_ps(_mm256_load_ps(b.nearHi[a] ? n.lo[a] : n.hi[a]), b.originFar[a]);
            enter = _mm256_max_ps(
                enter, _mm256_min_ps(_mm256_mul_ps(dn, b.invLo[a]), _mm256_mul_ps(dn, b.invHi[a])));
            exit = _mm256_min_ps(
                exit, _mm256_max_ps(_mm256_mul_ps(df, b.invLo[a]), _mm256_mul_ps(df, b.invHi[a])));
        }
        exit = _mm256_min_ps(_mm256_mul_ps(exit, farScale), _mm256_set1_ps(tMax));
        _mm256_store_ps(tNear, enter);
        return static_cast<uint32_t>(_mm256_movemask_ps(_mm256_cmp_ps(enter, exit, _CMP_LE_OQ)));
    }

    /// Triangle k of `b` against the eight rays: intersectTriangle()'s arithmetic per lane.
    /// Returns the lanes hit within their range; `t` receives the distances.
    static __m256 laneHits(const Tri4& b, int k, const PacketLanes& l, __m256& t) {
        const int kx = l.kx, ky = l.ky, kz = l.kz;
        const __m256 zero = _mm256_setzero_ps();
        auto shear = [&](const float(&v)[3][kLanes], __m256& x, __m256& y, __m256& z) {
            __m256 px = _mm256_sub_ps(_mm256_set1_ps(v[kx][k]), l.ox);
            __m256 py = _mm256_sub_ps(_mm256_set1_ps(v[ky][k]), l.oy);
            z = _mm256_sub_ps(_mm256_set1_ps(v[kz][k]), l.oz);
            x = _mm256_sub_ps(px, _mm256_mul_ps(l.sx, z));
            y = _mm256_sub_ps(py, _mm256_mul_ps(l.sy, z));
        };
        __m256 ax, ay, az, bx, by, bz, cx, cy, cz;
        shear(b.v0, ax, ay, az);
        shear(b.v1, bx, by, bz);
        shear(b.v2, cx, cy, cz);
        __m256 u = _mm256_sub_ps(_mm256_mul_ps(cx, by), _mm256_mul_ps(cy, bx));
        __m256 v = _mm256_sub_ps(_mm256_mul_ps(ax, cy), _mm256_mul_ps(ay, cx));
        __m256 w = _mm256_sub_ps(_mm256_mul_ps(bx, ay), _mm256_mul_ps(by, ax));
        __m256 anyNeg = _mm256_or_ps(
            _mm256_or_ps(_mm256_cmp_ps(u, zero, _CMP_LT_OQ), _mm256_cmp_ps(v, zero, _CMP_LT_OQ)),
            _mm256_cmp_ps(w, zero, _CMP_LT_OQ));
        __m256 anyPos = _mm256_or_ps(
            _mm256_or_ps(_mm256_cmp_ps(u, zero, _CMP_GT_OQ), _mm256_cmp_ps(v, zero, _CMP_GT_OQ)),
            _mm256_cmp_ps(w, zero, _CMP_GT_OQ));
        __m256 det = _mm256_add_ps(_mm256_add_ps(u, v), w);
        __m256 tScaled = _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(u, _mm256_mul_ps(l.sz, az)),
                                                     _mm256_mul_ps(v, _mm256_mul_ps(l.sz, bz))),
                                       _mm256_mul_ps(w, _mm256_mul_ps(l.sz, cz)));
        t = _mm256_div_ps(tScaled, det);
        __m256 ok =
            _mm256_andnot_ps(_mm256_and_ps(anyNeg, anyPos), _mm256_cmp_ps(det, zero, _CMP_NEQ_UQ));
        ok = _mm256_and_ps(ok, _mm256_cmp_ps(t, l.tMin, _CMP_GT_OQ));
        return _mm256_and_ps(ok, _mm256_cmp_ps(t, l.tMax, _CMP_LT_OQ));
    }

    /// The four triangles of `b` against the eight rays; each lane keeps its best hit by the
    /// closerHit rule.
    static void packetTriangles(const Tri4& b, const PacketLanes& l, float* bestT,
                                uint32_t* bestId) {
        __m256 bt = _mm256_load_ps(bestT);
        __m256i bid = _mm256_load_si256(reinterpret_cast<const __m256i*>(bestId));
        const __m256i flip = _mm256_set1_epi32(static_cast<int>(0x80000000u));
        for (int k = 0; k < kLanes; ++k) {
            if (b.id[k] == kEmpty) continue;
            __m256 t;
            __m256 ok = laneHits(b, k, l, t);
            __m256i id = _mm256_set1_epi32(static_cast<int>(b.id[k]));
            __m256 lowerId = _mm256_castsi256_ps(
                _mm256_cmpgt_epi32(_mm256_xor_si256(bid, flip), _mm256_xor_si256(id, flip)));
            __m256 better = _mm256_or_ps(_mm256_cmp_ps(t, bt, _CMP_LT_OQ),
                                         _mm256_and_ps(_mm256_cmp_ps(t, bt, _CMP_EQ_OQ), lowerId));
            __m256 take = _mm256_and_ps(ok, better);
            bt = _mm256_blendv_ps(bt, t, take);
            bid = _mm256_castps_si256(
                _mm256_blendv_ps(_mm256_castsi256_ps(bid), _mm256_castsi256_ps(id), take));
        }
        _mm256_store_ps(bestT, bt);
        _mm256_store_si256(reinterpret_cast<__m256i*>(bestId), bid);
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

}  // namespace glint::bvh::avx2

#pragma GCC pop_options
