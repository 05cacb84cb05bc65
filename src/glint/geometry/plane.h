#pragma once
/// Infinite planes. A plane has no finite bounds, so it cannot live in a BVH: accelerators keep
/// planes in a short list and test them beside their tree on every query (accel/bvh.h).

#include <optional>

#include "glint/core/ray.h"
#include "glint/math/transform.h"

namespace glint {

struct Plane {
    Vec3 point;   ///< World space: a point on the plane.
    Vec3 normal;  ///< World space, unit. Never flipped (like a triangle's face normal).

    /// The plane through object-space `point` with object-space `normal` (any non-zero
    /// length) under `worldFromObject`; nothing if the normal cannot be normalised.
    static std::optional<Plane> make(const Vec3& point, const Vec3& normal,
                                     const Transform& worldFromObject);
};

/// The float search: the plane n.x + w = 0, n unit.
struct PlaneSearch {
    Vec3f n;
    float w = 0;

    static PlaneSearch from(const Plane& p) {
        return {Vec3f(p.normal), static_cast<float>(-dot(p.normal, p.point))};
    }
};

/// On a crossing with tMin < t < tMax sets `t` and returns true; a ray parallel to the plane
/// (in it or not) misses.
inline bool intersectPlane(const PlaneSearch& p, const TraversalRay& ray, float& t) {
    float dn = dot(p.n, ray.dir);
    if (dn == 0) return false;
    float tHit = -(dot(p.n, ray.origin) + p.w) / dn;
    if (!(tHit > ray.tMin && tHit < ray.tMax)) return false;
    t = tHit;
    return true;
}

/// The crossing recomputed in double (`tFloat` if the double ray is parallel).
inline double refinePlaneHit(const Plane& p, const Ray& ray, float tFloat) {
    double dn = dot(p.normal, ray.dir);
    return dn != 0 ? dot(p.point - ray.origin, p.normal) / dn : tFloat;
}

}  // namespace glint
