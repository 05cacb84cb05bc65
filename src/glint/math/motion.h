#pragma once
/// Motion over a camera's shutter: a transform keyed at evenly spaced times from the shutter's
/// opening (time 0) to its closing (time 1), and the time of the rays a thread traces.
///
/// Between two keys a transform is interpolated as pbrt's AnimatedTransform does: each key's
/// linear part is split by polar decomposition into a rotation R and a stretch S (M = T R S),
/// then the translation and the stretch are interpolated linearly and the rotation along the
/// shorter arc (slerp). A rigid motion thus turns about the object's own origin, without the
/// shrinking of interpolated matrices; curved paths need more keys.

#include <array>
#include <cstdint>
#include <vector>

#include "glint/math/bbox.h"
#include "glint/math/transform.h"

namespace glint {

/// The shutter time, 0 (open) to 1 (closed), of the rays the calling thread traces: set by the
/// renderer for each camera sample (every ray of one path shares its camera ray's time), read
/// by the tests of moving primitives. 0 outside renders.
float shutterTime();
void setShutterTime(float u);

class MotionPath {
  public:
    MotionPath() = default;
    /// `keys` (at least one; invertible) at times 0, 1/(n-1), ..., 1.
    explicit MotionPath(const std::vector<Transform>& keys);

    /// The transform at time u (clamped to [0, 1]).
    Transform at(float u) const;
    /// What takes a thing placed by the first key to where it is at time u: at(u) x the first
    /// key's inverse (the identity at time 0).
    Transform delta(float u) const;
    /// Whether the keys differ (a path of equal keys does not move).
    bool moves() const { return moves_; }
    const std::vector<Transform>& keys() const { return keys_; }
    /// Bounds of `box`, placed as at time 0, over the whole shutter: the union of its images
    /// by delta() at many times, padded for the arcs between them.
    Bounds3f sweep(const Bounds3f& box) const;

  private:
    struct Parts {
        Vec3 translation;
        std::array<double, 4> rotation;  ///< Unit quaternion x, y, z, w.
        double stretch[3][3];
    };
    /// The interpolated matrix at time u (keys_.size() >= 2).
    Mat4 matrixAt(float u) const;

    std::vector<Transform> keys_;
    std::vector<Parts> parts_;
    Mat4 firstInverse_;  ///< The first key's inverse: delta() maps from it.
    uint64_t id_ = 0;    ///< This path's (and its copies') key in delta()'s per-thread cache.
    bool moves_ = false;
};

}  // namespace glint
