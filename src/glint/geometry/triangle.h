#pragma once
/// Triangles: stored in float as a vertex and two edges; searched in float, and the winning
/// hit refined in double from the same stored data.

#include <cmath>

#include "glint/core/ray.h"
#include "glint/math/bbox.h"

namespace glint {

struct Triangle {
    Vec3f p0, e1, e2;  ///< Vertex A and the edges B - A, C - A, world space.

    static Triangle fromVertices(const Vec3& a, const Vec3& b, const Vec3& c) {
        return {Vec3f(a), Vec3f(b - a), Vec3f(c - a)};
    }
    /// Unnormalised geometric normal (B - A) x (C - A): counter-clockwise faces point at the
    /// viewer. Never flipped, as in the course's renderer. Computed in double from the stored
    /// float edges, where each product is exact: it is zero exactly when the edges are parallel.
    Vec3 normalDirection() const { return cross(Vec3(e1), Vec3(e2)); }
    /// Zero area (collinear or repeated vertices) as stored. Primitives never keeps these.
    bool degenerate() const { return normalDirection() == Vec3(0); }
    Bounds3f bounds() const {
        Vec3 a(p0), b = a + Vec3(e1), c = a + Vec3(e2);
        return Bounds3f::enclosing(min(a, min(b, c)), max(a, max(b, c)));
    }
};

/// Moller-Trumbore test in float. On a hit with tMin < t < min(ray.tMax, hit.t) sets hit.t
/// and returns true. Edges count as inside; rays in the triangle's plane never hit. The
/// triangle must not be degenerate: for collinear vertices the float determinant can round to
/// a tiny non-zero value and report a meaningless hit (Primitives drops such triangles).
inline bool intersectTriangle(const Triangle& tri, const TraversalRay& ray, Hit& hit) {
    Vec3f pvec = cross(ray.dir, tri.e2);
    float det = dot(tri.e1, pvec);
    if (det == 0 || !std::isfinite(det)) return false;
    float inv = 1 / det;
    Vec3f tvec = ray.origin - tri.p0;
    float u = dot(tvec, pvec) * inv;
    if (!(u >= 0 && u <= 1)) return false;
    Vec3f qvec = cross(tvec, tri.e1);
    float v = dot(ray.dir, qvec) * inv;
    if (!(v >= 0 && u + v <= 1)) return false;
    float t = dot(tri.e2, qvec) * inv;
    if (!(t > ray.tMin && t < ray.tMax && t < hit.t)) return false;
    hit.t = t;
    return true;
}

/// A hit recomputed in double: distance and barycentrics of vertices B and C.
struct TriangleHit {
    double t, b1, b2;
};

/// The same test in double for a ray known to hit `tri` near `tFloat` (no range checks).
inline TriangleHit refineTriangleHit(const Triangle& tri, const Ray& ray, float tFloat) {
    Vec3 e1(tri.e1), e2(tri.e2);
    Vec3 pvec = cross(ray.dir, e2);
    double det = dot(e1, pvec);
    if (det == 0) return {tFloat, 0, 0};
    Vec3 tvec = ray.origin - Vec3(tri.p0);
    Vec3 qvec = cross(tvec, e1);
    return {dot(e2, qvec) / det, dot(tvec, pvec) / det, dot(ray.dir, qvec) / det};
}

}  // namespace glint
