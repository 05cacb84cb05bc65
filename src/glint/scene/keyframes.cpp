#include "glint/scene/keyframes.h"

#include <algorithm>
#include <cmath>

namespace glint {
namespace {

/// Scales the quaternion q[0..4) to unit length; false, leaving it, if it is zero.
bool normalise(double* q) {
    const double len = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    if (!(len > 0)) return false;
    for (int i = 0; i < 4; ++i) q[i] /= len;
    return true;
}

/// Spherical linear interpolation from unit quaternion a to b by s in [0, 1], along the
/// shorter arc (b or -b, whichever is nearer a: both are the same rotation).
void slerp(const double* a, const double* b, double s, double* out) {
    double cosine = a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3];
    const double sign = cosine < 0 ? -1 : 1;
    cosine *= sign;
    double wa = 1 - s, wb = s;
    if (cosine < 0.9995) {  // else nearly parallel: linear, then normalised, is exact enough
        const double angle = std::acos(std::min(cosine, 1.0));
        const double sine = std::sin(angle);
        wa = std::sin((1 - s) * angle) / sine;
        wb = std::sin(s * angle) / sine;
    }
    for (int i = 0; i < 4; ++i) out[i] = wa * a[i] + wb * sign * b[i];
    normalise(out);
}

}  // namespace

const char* interpolationName(Interpolation i) {
    switch (i) {
        case Interpolation::Step:
            return "STEP";
        case Interpolation::CubicSpline:
            return "CUBICSPLINE";
        default:
            return "LINEAR";
    }
}

std::string KeyframeTrack::problem() const {
    if (times.empty()) return "it has no keyframes";
    if (width == 0) return "its values have no components";
    for (size_t k = 0; k < times.size(); ++k) {
        if (!std::isfinite(times[k])) return "key time " + std::to_string(k) + " is not finite";
        if (k > 0 && !(times[k] > times[k - 1]))
            return "key times must increase, but time " + std::to_string(k) + " (" +
                   std::to_string(times[k]) + ") is not after time " + std::to_string(k - 1) +
                   " (" + std::to_string(times[k - 1]) + ")";
    }
    const size_t perKey = width * (interpolation == Interpolation::CubicSpline ? 3 : 1);
    if (values.size() != times.size() * perKey)
        return "it has " + std::to_string(times.size()) + " key times but " +
               std::to_string(values.size()) + " output values, where " +
               std::string(interpolationName(interpolation)) + " needs " +
               std::to_string(times.size() * perKey);
    for (size_t i = 0; i < values.size(); ++i)
        if (!std::isfinite(values[i]))
            return "output value " + std::to_string(i) + " is not finite";
    if (rotation) {
        if (width != 4) return "a rotation has 4 components";
        for (size_t k = 0; k < times.size(); ++k) {
            const double* q = &values[k * perKey + (perKey == 12 ? 4 : 0)];
            if (!(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3] > 0))
                return "the rotation of key " + std::to_string(k) + " is zero";
        }
    }
    return {};
}

void KeyframeTrack::sample(double t, double* out) const {
    const size_t n = times.size();
    const bool cubic = interpolation == Interpolation::CubicSpline;
    const size_t stride = cubic ? 3 * width : width;
    const size_t at = cubic ? width : 0;  // the value's offset within its key
    auto value = [&](size_t k) { return &values[k * stride + at]; };
    // A spline between two rotations may pass through zero (tangents as a file gives them):
    // the earlier key's rotation then.
    size_t k = 0;
    auto finish = [&] {
        if (rotation && !normalise(out)) {
            std::copy_n(value(k), width, out);
            normalise(out);
        }
    };
    // Clamped outside the keys.
    if (!(t > times.front()) || n == 1) {
        std::copy_n(value(0), width, out);
        return finish();
    }
    if (!(t < times.back())) {
        std::copy_n(value(n - 1), width, out);
        return finish();
    }
    // The key k with times[k] <= t < times[k + 1].
    k = static_cast<size_t>(std::upper_bound(times.begin(), times.end(), t) - times.begin()) - 1;
    const double d = times[k + 1] - times[k];
    const double s = (t - times[k]) / d;
    switch (interpolation) {
        case Interpolation::Step:
            std::copy_n(value(k), width, out);
            break;
        case Interpolation::Linear:
            if (rotation) {
                slerp(value(k), value(k + 1), s, out);
            } else {
                for (size_t i = 0; i < width; ++i)
                    out[i] = value(k)[i] + (value(k + 1)[i] - value(k)[i]) * s;
            }
            break;
        case Interpolation::CubicSpline: {
            const double s2 = s * s, s3 = s2 * s;
            const double h00 = 2 * s3 - 3 * s2 + 1, h10 = s3 - 2 * s2 + s;
            const double h01 = -2 * s3 + 3 * s2, h11 = s3 - s2;
            const double* outTangent = &values[k * stride + 2 * width];  // b_k
            const double* inTangent = &values[(k + 1) * stride];         // a_{k+1}
            for (size_t i = 0; i < width; ++i)
                out[i] = h00 * value(k)[i] + d * h10 * outTangent[i] + h01 * value(k + 1)[i] +
                         d * h11 * inTangent[i];
            break;
        }
    }
    finish();
}

}  // namespace glint
