#pragma once
/// Triangles: three float vertices, searched with a watertight float test, and the winning
/// hit refined in double from the same stored vertices.

#include <cmath>

#include "glint/core/ray.h"
#include "glint/math/bbox.h"

namespace glint {

struct Triangle {
    Vec3f v0, v1, v2;  ///< World space, counter-clockwise seen from the front.

    static Triangle fromVertices(const Vec3& a, const Vec3& b, const Vec3& c) {
        return {Vec3f(a), Vec3f(b), Vec3f(c)};
    }
    /// Unnormalised geometric normal (B - A) x (C - A): counter-clockwise faces point at the
    /// viewer. Never flipped, as in the course's renderer. In double from the float vertices:
    /// the differences are exact and so is each product, so it is zero exactly when the
    /// stored triangle has zero area.
    Vec3 normalDirection() const {
        Vec3 a(v0);
        return cross(Vec3(v1) - a, Vec3(v2) - a);
    }
    /// Zero area (collinear or repeated vertices) as stored. Primitives never keeps these.
    bool degenerate() const { return normalDirection() == Vec3(0); }
    Bounds3f bounds() const {
        Bounds3f b;
        b.extend(v0);
        b.extend(v1);
        b.extend(v2);
        return b;
    }
};

/// The watertight ray-triangle test of Woop, Benthin and Wald ("Watertight Ray/Triangle
/// Intersection", JCGT 2013) in float, without its double-precision fallback: vertices are
/// moved to the ray origin and sheared so the ray runs along +z; the signs of the three 2D
/// edge functions decide inside/outside, computed the same way for both triangles sharing an
/// edge, so no ray slips through between them. Edges count as inside; back faces are hit.
///
/// On a hit with tMin < t < tMax, sets `t` and returns true. The SIMD leaf kernels repeat these
/// exact operations lane by lane, so both give bit-identical results. The triangle must not be
/// degenerate (Primitives drops those).
inline bool intersectTriangle(const Triangle& tri, const TraversalRay& ray, float& t) {
    const int kx = ray.kx, ky = ray.ky, kz = ray.kz;
    Vec3f a = tri.v0 - ray.origin, b = tri.v1 - ray.origin, c = tri.v2 - ray.origin;
    float ax = a[kx] - ray.sx * a[kz], ay = a[ky] - ray.sy * a[kz];
    float bx = b[kx] - ray.sx * b[kz], by = b[ky] - ray.sy * b[kz];
    float cx = c[kx] - ray.sx * c[kz], cy = c[ky] - ray.sy * c[kz];
    float u = cx * by - cy * bx;
    float v = ax * cy - ay * cx;
    float w = bx * ay - by * ax;
    if ((u < 0 || v < 0 || w < 0) && (u > 0 || v > 0 || w > 0)) return false;
    float det = u + v + w;
    if (det == 0) return false;
    float tScaled = u * (ray.sz * a[kz]) + v * (ray.sz * b[kz]) + w * (ray.sz * c[kz]);
    float tHit = tScaled / det;
    if (!(tHit > ray.tMin && tHit < ray.tMax)) return false;
    t = tHit;
    return true;
}

/// A hit recomputed in double: distance and barycentrics of vertices B and C.
struct TriangleHit {
    double t, b1, b2;
};

/// Moller-Trumbore in double for a ray known to hit `tri` near `tFloat` (no range checks).
inline TriangleHit refineTriangleHit(const Triangle& tri, const Ray& ray, float tFloat) {
    Vec3 v0(tri.v0), e1 = Vec3(tri.v1) - v0, e2 = Vec3(tri.v2) - v0;
    Vec3 pvec = cross(ray.dir, e2);
    double det = dot(e1, pvec);
    if (det == 0) return {tFloat, 0, 0};
    Vec3 tvec = ray.origin - v0;
    Vec3 qvec = cross(tvec, e1);
    return {dot(e2, qvec) / det, dot(tvec, pvec) / det, dot(ray.dir, qvec) / det};
}

}  // namespace glint
