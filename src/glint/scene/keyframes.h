#pragma once
/// Keyframed values over time, as glTF animation samplers hold them (glTF 2.0, section 3.11
/// "Animations" and appendix C "Interpolation"): strictly increasing key times, a value of N
/// components per key, and one of three interpolations.
///
/// - **STEP**: the value of the last key at or before t.
/// - **LINEAR**: linear between the two keys around t; for rotations (unit quaternions x, y, z,
///   w) spherical linear interpolation along the shorter arc.
/// - **CUBICSPLINE**: a cubic Hermite spline; each key holds three values in the order in-tangent
///   a_k, value v_k, out-tangent b_k. Between keys k and k+1, with d = t_{k+1} - t_k and
///   s = (t - t_k) / d:
///   v(s) = (2s^3 - 3s^2 + 1) v_k + d (s^3 - 2s^2 + s) b_k + (-2s^3 + 3s^2) v_{k+1}
///          + d (s^3 - s^2) a_{k+1};
///   a rotation's result is normalised.
///
/// Before the first key a track holds its first value, after the last its last (glTF leaves
/// the value outside the keys to the implementation; every viewer clamps).

#include <cstddef>
#include <string>
#include <vector>

namespace glint {

enum class Interpolation { Step, Linear, CubicSpline };

/// "STEP", "LINEAR", "CUBICSPLINE": glTF's names, for messages.
const char* interpolationName(Interpolation i);

/// One animated quantity: a translation or scale (3 components), a rotation (4, a unit
/// quaternion x, y, z, w), or morph-target weights (one per target).
struct KeyframeTrack {
    std::vector<double> times;   ///< Strictly increasing, finite.
    std::vector<double> values;  ///< times.size() x width values, x 3 for CUBICSPLINE.
    size_t width = 0;            ///< Components of one value.
    Interpolation interpolation = Interpolation::Linear;
    bool rotation = false;  ///< Values are unit quaternions: slerped, or normalised.

    /// Why this track cannot be sampled (no keys, times not finite or not increasing, the
    /// wrong number of values, a value not finite, a rotation of zero length), or "".
    std::string problem() const;

    /// The value at time t into out[0 .. width). The track must have no problem().
    void sample(double t, double* out) const;
};

}  // namespace glint
