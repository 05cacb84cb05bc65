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
/// (the distance to a point light for shadow rays; infinity otherwise).
inline Ray spawnRay(const Vec3& p, const Vec3& dir, double sceneOffset,
                    double maxDistance = kInfinity) {
    double eps = spawnOffset(p, sceneOffset);
    return Ray{p + dir * eps, dir, 0, maxDistance - eps};
}

}  // namespace glint
