#include "glint/math/motion.h"

#include <algorithm>
#include <atomic>
#include <cmath>

namespace glint {
namespace {

thread_local float tShutterTime = 0;

using M3 = std::array<std::array<double, 3>, 3>;

M3 linearPart(const Mat4& m) {
    M3 a{};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) a[i][j] = m.m[i][j];
    return a;
}

double det3(const M3& a) {
    return a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) -
           a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
           a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
}

/// The inverse transpose of `a` (invertible).
M3 inverseTranspose(const M3& a) {
    const double d = det3(a);
    M3 c{};  // cofactors: the inverse transpose times the determinant
    c[0][0] = a[1][1] * a[2][2] - a[1][2] * a[2][1];
    c[0][1] = a[1][2] * a[2][0] - a[1][0] * a[2][2];
    c[0][2] = a[1][0] * a[2][1] - a[1][1] * a[2][0];
    c[1][0] = a[0][2] * a[2][1] - a[0][1] * a[2][2];
    c[1][1] = a[0][0] * a[2][2] - a[0][2] * a[2][0];
    c[1][2] = a[0][1] * a[2][0] - a[0][0] * a[2][1];
    c[2][0] = a[0][1] * a[1][2] - a[0][2] * a[1][1];
    c[2][1] = a[0][2] * a[1][0] - a[0][0] * a[1][2];
    c[2][2] = a[0][0] * a[1][1] - a[0][1] * a[1][0];
    for (auto& row : c)
        for (double& x : row) x /= d;
    return c;
}

/// The rotation of the polar decomposition of `a` (det(a) > 0): R = lim R_{k+1} = (R_k +
/// R_k^-T) / 2 from R_0 = a (Higham's iteration; a few steps for the transforms of scenes).
M3 polarRotation(const M3& a) {
    M3 r = a;
    for (int k = 0; k < 100; ++k) {
        const M3 it = inverseTranspose(r);
        double change = 0;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) {
                const double next = 0.5 * (r[i][j] + it[i][j]);
                change = std::max(change, std::abs(next - r[i][j]));
                r[i][j] = next;
            }
        if (change < 1e-14) break;
    }
    return r;
}

std::array<double, 4> quaternionOf(const M3& r) {
    std::array<double, 4> q{};  // x, y, z, w
    const double trace = r[0][0] + r[1][1] + r[2][2];
    if (trace > 0) {
        const double s = std::sqrt(trace + 1) * 2;
        q = {(r[2][1] - r[1][2]) / s, (r[0][2] - r[2][0]) / s, (r[1][0] - r[0][1]) / s, s / 4};
    } else if (r[0][0] > r[1][1] && r[0][0] > r[2][2]) {
        const double s = std::sqrt(1 + r[0][0] - r[1][1] - r[2][2]) * 2;
        q = {s / 4, (r[0][1] + r[1][0]) / s, (r[0][2] + r[2][0]) / s, (r[2][1] - r[1][2]) / s};
    } else if (r[1][1] > r[2][2]) {
        const double s = std::sqrt(1 + r[1][1] - r[0][0] - r[2][2]) * 2;
        q = {(r[0][1] + r[1][0]) / s, s / 4, (r[1][2] + r[2][1]) / s, (r[0][2] - r[2][0]) / s};
    } else {
        const double s = std::sqrt(1 + r[2][2] - r[0][0] - r[1][1]) * 2;
        q = {(r[0][2] + r[2][0]) / s, (r[1][2] + r[2][1]) / s, s / 4, (r[1][0] - r[0][1]) / s};
    }
    const double len = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    for (double& c : q) c /= len;
    return q;
}

M3 rotationOf(const std::array<double, 4>& q) {
    const double x = q[0], y = q[1], z = q[2], w = q[3];
    return {{{1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)},
             {2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)},
             {2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)}}};
}

std::array<double, 4> slerp(std::array<double, 4> a, std::array<double, 4> b, double s) {
    double cosine = a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3];
    if (cosine < 0) {  // the shorter arc: -b is the same rotation
        for (double& c : b) c = -c;
        cosine = -cosine;
    }
    double wa = 1 - s, wb = s;
    if (cosine < 0.9995) {
        const double angle = std::acos(std::min(cosine, 1.0)), sine = std::sin(angle);
        wa = std::sin((1 - s) * angle) / sine;
        wb = std::sin(s * angle) / sine;
    }
    std::array<double, 4> q{};
    double len = 0;
    for (int i = 0; i < 4; ++i) {
        q[i] = wa * a[i] + wb * b[i];
        len += q[i] * q[i];
    }
    for (double& c : q) c /= std::sqrt(len);
    return q;
}

}  // namespace

float shutterTime() { return tShutterTime; }
void setShutterTime(float u) { tShutterTime = u; }

MotionPath::MotionPath(const std::vector<Transform>& keys) : keys_(keys) {
    static std::atomic<uint64_t> paths{0};
    id_ = ++paths;
    if (!keys_.empty()) firstInverse_ = keys_.front().inverseMatrix();
    for (const Transform& k : keys_) {
        const Mat4 m = k.matrix();
        M3 a = linearPart(m);
        // A mirroring key: decompose -a (a rotation times a negated stretch).
        const double sign = det3(a) < 0 ? -1 : 1;
        for (auto& row : a)
            for (double& x : row) x *= sign;
        const M3 r = polarRotation(a);
        Parts p;
        p.translation = {m.m[0][3], m.m[1][3], m.m[2][3]};
        p.rotation = quaternionOf(r);
        for (int i = 0; i < 3; ++i)  // S = R^T a, with the sign given back
            for (int j = 0; j < 3; ++j)
                p.stretch[i][j] =
                    sign * (r[0][i] * a[0][j] + r[1][i] * a[1][j] + r[2][i] * a[2][j]);
        parts_.push_back(p);
        const Mat4 first = keys_.front().matrix();
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 4; ++j) moves_ = moves_ || m.m[i][j] != first.m[i][j];
    }
}

Mat4 MotionPath::matrixAt(float time) const {
    const double u =
        std::clamp(static_cast<double>(time), 0.0, 1.0) * static_cast<double>(keys_.size() - 1);
    const size_t k = std::min(static_cast<size_t>(u), keys_.size() - 2);
    const double s = u - static_cast<double>(k);
    if (s == 0) return keys_[k].matrix();
    const Parts &a = parts_[k], &b = parts_[k + 1];
    const M3 r = rotationOf(slerp(a.rotation, b.rotation, s));
    Mat4 m;
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) {
            double v = 0;
            for (int l = 0; l < 3; ++l)
                v += r[i][l] * ((1 - s) * a.stretch[l][j] + s * b.stretch[l][j]);
            m.m[i][j] = v;
        }
        m.m[i][3] = (1 - s) * a.translation[i] + s * b.translation[i];
    }
    return m;
}

Transform MotionPath::at(float time) const {
    if (keys_.size() < 2) return keys_.empty() ? Transform() : keys_.front();
    if (std::optional<Transform> t = Transform::fromMatrix(matrixAt(time))) return *t;
    // Between invertible keys the interpolated stretch can only be singular in contrived
    // paths; the nearer key stands in then.
    const double u =
        std::clamp(static_cast<double>(time), 0.0, 1.0) * static_cast<double>(keys_.size() - 1);
    return keys_[std::min(static_cast<size_t>(std::lround(u)), keys_.size() - 1)];
}

Transform MotionPath::delta(float u) const {
    if (!moves_) return Transform();
    // Every ray of a camera sample has its time: the rays of one path ask again and again for
    // the same delta, so each thread keeps the last few (a path's id and time make the key;
    // the value is what computing it gives, so images do not depend on the cache).
    struct Cached {
        uint64_t path = 0;
        float u = 0;
        Transform delta;
    };
    thread_local std::array<Cached, 8> cache;
    Cached& c = cache[id_ % cache.size()];
    if (c.path == id_ && c.u == u) return c.delta;
    std::optional<Transform> t = Transform::fromMatrix(matrixAt(u) * firstInverse_);
    if (!t) t = Transform::fromMatrix(at(u).matrix() * firstInverse_);
    c = {id_, u, t.value_or(Transform())};
    return c.delta;
}

Bounds3f MotionPath::sweep(const Bounds3f& box) const {
    if (box.empty() || keys_.empty()) return box;
    // Steps of the shutter at which the box is placed: 64, both ends included; one if still.
    const int steps = moves_ ? 64 : 0;
    Bounds3f out;
    for (int i = 0; i <= steps; ++i) {
        const Transform t =
            delta(steps == 0 ? 0.0f : static_cast<float>(i) / static_cast<float>(steps));
        for (int c = 0; c < 8; ++c) {
            const Vec3 corner(c & 1 ? box.hi.x : box.lo.x, c & 2 ? box.hi.y : box.lo.y,
                              c & 4 ? box.hi.z : box.lo.z);
            out.extend(Vec3f(t.point(corner)));
        }
    }
    if (steps > 0) {
        // Between samples a turning corner leaves the chord by at most r (1 - cos(a / 2)) for
        // a turn of a per step; 1% of the box's size covers steps of up to 16 degrees.
        const Vec3f size = out.hi - out.lo;
        const float pad = 0.01f * std::max({size.x, size.y, size.z});
        out.lo = out.lo - Vec3f(pad);
        out.hi = out.hi + Vec3f(pad);
    }
    return out;
}

}  // namespace glint
