#pragma once
/// Spheres under an affine transform (ellipsoids under non-uniform scale).
///
/// The search runs in float in the unit sphere's space; the winning hit is refined in double
/// in the sphere's object space. Both use the numerically robust quadratic of Haines et al.,
/// "Precision Improvements for Ray/Sphere Intersection" (Ray Tracing Gems, 2019, ch. 7): the
/// textbook b^2 - 4ac loses most digits in float when the sphere is small relative to its
/// distance, enough to put hit points inside the sphere and cause shadow acne.

#include <cmath>
#include <utility>

#include "glint/core/ray.h"
#include "glint/geometry/shape_search.h"
#include "glint/math/transform.h"

namespace glint {

struct Sphere {
    Vec3 center;        ///< Object space.
    double radius = 1;  ///< Object space, positive.
    Transform worldFromObject;

    Bounds3f bounds() const { return worldFromObject.ballBounds(center, radius); }
};

/// What the float search needs: the map from world space to the space where the sphere is
/// the unit sphere at the origin.
ShapeSearch sphereSearch(const Sphere& s);

namespace detail {
/// Roots t0 <= t1 of |o + t d|^2 = r^2, or false. Robust against cancellation.
template <typename T>
inline bool sphereRoots(const Vec3T<T>& o, const Vec3T<T>& d, T r2, T& t0, T& t1) {
    T a = dot(d, d);
    if (!(a > 0)) return false;
    T b = -dot(o, d);  // a * (parameter of the point closest to the centre)
    Vec3T<T> l = o + d * (b / a);
    T disc = a * (r2 - dot(l, l));
    if (!(disc >= 0)) return false;
    T root = std::sqrt(disc);
    T q = b >= 0 ? b + root : b - root;
    T c = dot(o, o) - r2;
    t0 = c / q;
    t1 = q / a;
    if (!(t0 <= t1)) std::swap(t0, t1);
    return true;
}
}  // namespace detail

/// On a hit with tMin < t < tMax sets `t` (the nearer such root) and returns true. `t` is the
/// world-ray parameter: the mapped direction is not renormalised.
/// `s` must be a sphere's record (its kind is not looked at).
inline bool intersectSphere(const ShapeSearch& s, const TraversalRay& ray, float& t) {
    const auto& m = s.m;
    Vec3f o(m[0][0] * ray.origin.x + m[0][1] * ray.origin.y + m[0][2] * ray.origin.z + m[0][3],
            m[1][0] * ray.origin.x + m[1][1] * ray.origin.y + m[1][2] * ray.origin.z + m[1][3],
            m[2][0] * ray.origin.x + m[2][1] * ray.origin.y + m[2][2] * ray.origin.z + m[2][3]);
    Vec3f d(m[0][0] * ray.dir.x + m[0][1] * ray.dir.y + m[0][2] * ray.dir.z,
            m[1][0] * ray.dir.x + m[1][1] * ray.dir.y + m[1][2] * ray.dir.z,
            m[2][0] * ray.dir.x + m[2][1] * ray.dir.y + m[2][2] * ray.dir.z);
    float t0, t1;
    if (!detail::sphereRoots(o, d, 1.0f, t0, t1)) return false;
    float tHit = t0 > ray.tMin ? t0 : t1;
    if (!(tHit > ray.tMin && tHit < ray.tMax)) return false;
    t = tHit;
    return true;
}

/// The hit near `tFloat` recomputed in double in object space; returns t and the object-space
/// hit point relative to the centre (the unnormalised object-space normal).
inline double refineSphereHit(const Sphere& s, const Ray& ray, float tFloat, Vec3& local) {
    Vec3 o = s.worldFromObject.inversePoint(ray.origin) - s.center;
    Vec3 d = s.worldFromObject.inverseVector(ray.dir);
    double t0, t1, t = tFloat;
    if (detail::sphereRoots(o, d, s.radius * s.radius, t0, t1))
        t = std::abs(t0 - tFloat) <= std::abs(t1 - tFloat) ? t0 : t1;
    local = o + d * t;
    return t;
}

}  // namespace glint
