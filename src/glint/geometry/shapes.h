#pragma once
/// Boxes, cylinders, cones and disks under an affine transform, each searched in its canonical
/// space (shape_search.h):
///
///   box       [-1, 1]^3
///   cylinder  x^2 + y^2 <= 1, 0 <= z <= 1: the side and two caps
///   cone      sqrt(x^2 + y^2) <= 1 + (k - 1) z, 0 <= z <= 1, k in [0, 1]: the wide end at
///             z = 0; a cap at z = 1 unless k = 0 (a pointed cone)
///   disk      z = 0, x^2 + y^2 <= 1
///
/// The closed shapes are solids: the search computes the span of the ray inside the shape (the
/// intersection of slabs and of the inside of a quadric) and returns its entry, or its exit for
/// a ray that starts inside, exactly as spheres do. Seams between side and caps cannot leak:
/// both bound one span. The float search finds the hit; the winner is refined in double
/// (refineShapeHit) and its normal computed there, outward, mapped by the inverse transpose.

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "glint/core/ray.h"
#include "glint/geometry/shape_search.h"
#include "glint/geometry/sphere.h"
#include "glint/math/bbox.h"
#include "glint/math/transform.h"

namespace glint {

/// A box, cylinder, cone or disk (not a sphere: see sphere.h): its canonical form and the map
/// from canonical to world space, which holds the shape's own size and placement as well as
/// the transform it was created under.
struct Shape {
    ShapeKind kind = ShapeKind::Box;
    double k = 1;  ///< Cone: radius at z = 1 relative to the radius at z = 0, in [0, 1].
    Transform worldFromCanonical;

    /// World-space bounds, padded by a small fraction of the shape's size and coordinates so
    /// that float rounding in the box and shape tests cannot make them disagree.
    Bounds3f bounds() const;
    ShapeSearch search() const {
        return ShapeSearch::from(worldFromCanonical.inverseMatrix(), kind, k);
    }
};

/// World-space bounds [lo, hi] widened by a small fraction of their size and coordinates (16
/// float ulps): a float search in another space and the float box test round differently, and
/// a hit that the one finds at a silhouette must not lie outside the box that the other tests.
Bounds3f paddedSearchBounds(const Vec3& lo, const Vec3& hi);

/// objectFromCanonical placements from the scene format's parameters (object space). The
/// parameters must describe a proper shape (the loader checks): corners differing on every
/// axis, distinct end points, positive radii (one of a cone's may be 0), a non-zero normal.
Mat4 boxPlacement(const Vec3& corner0, const Vec3& corner1);
Mat4 cylinderPlacement(const Vec3& end0, const Vec3& end1, double radius);
/// The wider end goes to z = 0; `k` receives the narrower radius divided by the wider one.
Mat4 conePlacement(const Vec3& end0, double radius0, const Vec3& end1, double radius1, double& k);
Mat4 diskPlacement(const Vec3& center, const Vec3& normal, double radius);

namespace detail {

/// The parameters [enter, exit] of a ray inside a convex shape, narrowed one constraint at a
/// time. NaN bounds (0 * inf from a ray lying in a bounding plane) leave it unchanged.
template <typename T>
struct Span {
    T enter = -std::numeric_limits<T>::infinity();
    T exit = std::numeric_limits<T>::infinity();
    bool empty = false;

    void clip(T lo, T hi) {
        enter = std::max(enter, lo);
        exit = std::min(exit, hi);
    }
    /// Keeps the part where lo <= o + t d <= hi (one coordinate).
    void slab(T o, T d, T lo, T hi) {
        if (d == 0) {
            empty = empty || !(o >= lo && o <= hi);
            return;
        }
        T inv = 1 / d;
        T t0 = (lo - o) * inv, t1 = (hi - o) * inv;
        if (inv < 0) std::swap(t0, t1);
        clip(t0, t1);
    }
    bool hit() const { return !empty && enter <= exit; }
};

/// Keeps the part inside the infinite cylinder x^2 + y^2 <= 1, with the robust quadratic of
/// the sphere (sphere.h) in the xy plane.
template <typename T>
void cylinderSide(Span<T>& s, const Vec3T<T>& o, const Vec3T<T>& d) {
    Vec3T<T> o2(o.x, o.y, 0), d2(d.x, d.y, 0);
    if (!(dot(d2, d2) >= std::numeric_limits<T>::min())) {  // along the axis
        s.empty = s.empty || !(dot(o2, o2) <= 1);
        return;
    }
    T t0, t1;
    if (!sphereRoots(o2, d2, T(1), t0, t1)) {
        s.empty = true;
        return;
    }
    s.clip(t0, t1);
}

/// Keeps the part inside the cone x^2 + y^2 <= w^2, w = 1 - (1 - k) z >= 0 (the nappe that
/// holds the canonical cone; the slab 0 <= z <= 1 is applied separately). The ray is first
/// moved to its point nearest the middle of the cone, so the quadratic's coefficients stay of
/// the cone's size and do not cancel in float for distant origins.
template <typename T>
void coneSide(Span<T>& s, const Vec3T<T>& o, const Vec3T<T>& d, T k) {
    constexpr T inf = std::numeric_limits<T>::infinity();
    const T slope = 1 - k;
    T dd = dot(d, d);
    if (!(dd > 0)) {
        s.empty = true;
        return;
    }
    T tc = (T(0.5) * d.z - dot(o, d)) / dd;
    Vec3T<T> p = o + d * tc;
    // Q(u) = a u^2 + 2 b u + c <= 0 for the point p + u d.
    T w0 = 1 - slope * p.z, w1 = -slope * d.z;
    T a = d.x * d.x + d.y * d.y - w1 * w1;
    T b = p.x * d.x + p.y * d.y - w0 * w1;
    T c = p.x * p.x + p.y * p.y - w0 * w0;
    if (!(std::abs(a) >= std::numeric_limits<T>::min())) {  // parallel to the surface: linear
        if (b == 0) {
            s.empty = s.empty || c > 0;
        } else {
            T u = -c / (2 * b);
            if (b > 0)
                s.clip(-inf, tc + u);
            else
                s.clip(tc + u, inf);
        }
        return;
    }
    T disc = b * b - a * c;
    if (!(disc >= 0)) {
        // For a < 0 the line crosses both nappes and disc >= 0 exactly; only rounding is left.
        if (a > 0 || std::isnan(disc)) {
            s.empty = true;
            return;
        }
        disc = 0;
    }
    T root = std::sqrt(disc);
    T q = b >= 0 ? -(b + root) : root - b;
    T u0 = 0, u1 = 0;
    if (q != 0) {
        u0 = c / q;
        u1 = q / a;
        if (u0 > u1) std::swap(u0, u1);
    }
    if (a > 0)
        s.clip(tc + u0, tc + u1);  // inside between the roots
    else if (w1 > 0)
        s.clip(tc + u1, inf);  // outside them: keep the half where w grows, the lower nappe
    else
        s.clip(-inf, tc + u0);
}

/// The span of a ray inside a canonical box, cylinder or cone.
template <typename T>
Span<T> solidSpan(ShapeKind kind, T k, const Vec3T<T>& o, const Vec3T<T>& d) {
    Span<T> s;
    if (kind == ShapeKind::Box) {
        for (int a = 0; a < 3; ++a) s.slab(o[a], d[a], T(-1), T(1));
        return s;
    }
    s.slab(o.z, d.z, T(0), T(1));
    if (kind == ShapeKind::Cylinder)
        cylinderSide(s, o, d);
    else
        coneSide(s, o, d, k);
    return s;
}

/// The ray's parameter where it crosses the canonical disk, if it does.
template <typename T>
bool diskHit(const Vec3T<T>& o, const Vec3T<T>& d, T& t) {
    if (d.z == 0) return false;
    t = -o.z / d.z;
    T x = o.x + t * d.x, y = o.y + t * d.y;
    return x * x + y * y <= 1;
}

}  // namespace detail

/// Any bounded shape's float search: on a hit with tMin < t < tMax sets `t` (the entry into
/// a solid, or its exit for a ray starting inside) and returns true.
[[gnu::always_inline]] inline bool intersectShape(const ShapeSearch& s, const TraversalRay& ray,
                                                  float& t) {
    if (s.kind == ShapeKind::Sphere) return intersectSphere(s, ray, t);
    Vec3f o, d;
    s.map(ray, o, d);
    float tHit;
    if (s.kind == ShapeKind::Disk) {
        if (!detail::diskHit(o, d, tHit)) return false;
    } else {
        detail::Span<float> span = detail::solidSpan(s.kind, s.k, o, d);
        if (!span.hit()) return false;
        tHit = span.enter > ray.tMin ? span.enter : span.exit;
    }
    if (!(tHit > ray.tMin && tHit < ray.tMax)) return false;
    t = tHit;
    return true;
}

/// The hit near `tFloat` recomputed in double in canonical space: returns t and sets `local`,
/// the canonical hit point.
double refineShapeHit(const Shape& s, const Ray& ray, float tFloat, Vec3& local);

/// Outward unit normal in canonical space at (or nearest to) canonical point `p`: that of the
/// face, side or cap closest to it.
Vec3 canonicalNormal(ShapeKind kind, double k, const Vec3& p);

}  // namespace glint
