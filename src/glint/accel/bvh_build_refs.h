#pragma once
/// What the BVH builder works on: one reference per primitive (its box), ranges of them, and the
/// four-wide box arithmetic both are computed with. Internal to the builder (bvh_build*.cpp).

#include <algorithm>
#include <cstdint>
#include <limits>

#include "glint/math/bbox.h"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace glint::bvh::builder {

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
    uint32_t shape;  ///< 1 for shapes (spheres, boxes, instances, ...), 0 for triangles.

    V4 lo4() const { return V4::load(lo); }
    V4 hi4() const { return V4::load(hi); }
    float centroid2(int axis) const { return lo[axis] + hi[axis]; }
};

/// Refs [begin, end) of the build's array, with what deciding how to split them needs.
struct Range {
    uint32_t begin = 0, end = 0, shapes = 0;
    Box4 bounds, centroids;  ///< Centroids as lo + hi.

    uint32_t size() const { return end - begin; }
    uint32_t triangles() const { return size() - shapes; }

    /// Extends the bounds, centroid bounds and shape count by `p` (begin and end are the
    /// caller's).
    void add(const PrimRef& p) {
        V4 l = p.lo4(), h = p.hi4();
        bounds.extend(l, h);
        centroids.extend(l + h);
        shapes += p.shape;
    }
};

}  // namespace glint::bvh::builder
