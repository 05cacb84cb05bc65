#pragma once
/// The one rule for where secondary rays (shadow, reflection) start.
///
/// The course's renderer moves the origin 0.001 scene units along the new direction; its
/// reference images depend on exactly that (see docs/correctness.md). Glint keeps that offset
/// for scenes of unit size or larger and adapts it at both ends of the scale:
///  - small scenes: the absolute part is 0.001 times the scene's extent when that is below 1,
///    so a scene a thousand times smaller behaves like the same scene at full size;
///  - large coordinates: the offset never drops below 2^-16 of the point's largest coordinate
///    (about 128 float ulps: traversal is in float), where 0.001 would vanish in rounding.

#include <algorithm>
#include <cmath>

#include "glint/core/ray.h"

namespace glint {

/// The course's secondary-ray offset, in scene units, for scenes at least one unit across.
constexpr double kCourseSpawnOffset = 1e-3;
/// Relative part of the offset: a fraction of the magnitude of the coordinates.
constexpr double kRelativeSpawnOffset = 1.0 / 65536.0;

/// Absolute offset for a scene whose bounds have largest extent `sceneExtent`.
inline double sceneSpawnOffset(double sceneExtent) {
    return kCourseSpawnOffset * std::clamp(sceneExtent, 0.0, 1.0);
}

/// Offset to apply at point `p` in a scene with absolute offset `sceneOffset`.
inline double spawnOffset(const Vec3& p, double sceneOffset) {
    return std::max(sceneOffset, kRelativeSpawnOffset * maxComponent(abs(p)));
}

/// A ray leaving surface point `p` in unit direction `dir`, ending `maxDistance` from `p`
/// (the distance to a point light for shadow rays; infinity otherwise). The course's rule:
/// the Whitted integrator's.
inline Ray spawnRay(const Vec3& p, const Vec3& dir, double sceneOffset,
                    double maxDistance = kInfinity) {
    double eps = spawnOffset(p, sceneOffset);
    return Ray{p + dir * eps, dir, 0, maxDistance - eps};
}

/// The path tracer's rule: the origin moved by the same offset off the surface along its
/// geometric normal `ng` (to the side `dir` leaves to), not along `dir`. Moved along `dir`, a
/// ray leaving a floor point within the offset of a wall towards that wall starts beyond the
/// wall's plane and escapes the room through the corner: thin lines of the sky's light along
/// every inside corner of a room (issue 22). Along the normal the origin stays on the
/// surface's side, at the offset's distance from its plane whatever the angle (along `dir`,
/// only the offset times the cosine at grazing angles).
inline Ray spawnRayOffSurface(const Vec3& p, const Vec3& ng, const Vec3& dir, double sceneOffset,
                              double maxDistance = kInfinity) {
    const double eps = spawnOffset(p, sceneOffset);
    const Vec3 origin = p + ng * (dot(dir, ng) >= 0 ? eps : -eps);
    return Ray{origin, dir, 0, maxDistance};
}

/// The path tracer's shadow ray from surface point `p` (geometric normal `ng`) towards a light
/// `distance` away in unit direction `wi` (infinite: a light at infinity). The origin leaves
/// the surface as spawnRayOffSurface's does, and the ray is aimed from there at the light's
/// point, ending the offset short of it (its own surface lies there): kept along `wi`, the
/// ray would end past the plane of a light seen at a grazing angle, and find the light itself
/// in the way.
inline Ray shadowRayOffSurface(const Vec3& p, const Vec3& ng, const Vec3& wi, double distance,
                               double sceneOffset) {
    if (!std::isfinite(distance)) return spawnRayOffSurface(p, ng, wi, sceneOffset);
    const Vec3 target = p + wi * distance;
    Ray r = spawnRayOffSurface(p, ng, wi, sceneOffset);
    const Vec3 d = target - r.origin;
    const double len = length(d);
    r.dir = d / len;
    r.tMax = len - spawnOffset(target, sceneOffset);
    return r;
}

}  // namespace glint
