#include "glint/math/transform.h"

#include <cmath>
#include <utility>

namespace glint {

std::optional<Transform> Transform::fromMatrix(const Mat4& m) {
    std::optional<Mat4> inv = glint::inverse(m);
    if (!inv) return std::nullopt;
    Transform t;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 4; ++j) {
            t.m_[i][j] = m.m[i][j];
            t.inv_[i][j] = inv->m[i][j];
            if (!std::isfinite(t.m_[i][j]) || !std::isfinite(t.inv_[i][j])) return std::nullopt;
        }
    return t;
}

Bounds3f Transform::ballBounds(const Vec3& center, double radius) const {
    Vec3 c = point(center);
    Vec3 half;
    for (int i = 0; i < 3; ++i)
        half[i] = std::abs(radius) *
                  std::sqrt(m_[i][0] * m_[i][0] + m_[i][1] * m_[i][1] + m_[i][2] * m_[i][2]);
    return Bounds3f::enclosing(c - half, c + half);
}

Transform Transform::inverse() const {
    Transform t = *this;
    std::swap(t.m_, t.inv_);
    return t;
}

namespace {
Mat4 toMat4(const double (&a)[3][4]) {
    Mat4 r;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 4; ++j) r.m[i][j] = a[i][j];
    return r;
}
}  // namespace

Mat4 Transform::matrix() const { return toMat4(m_); }
Mat4 Transform::inverseMatrix() const { return toMat4(inv_); }

bool Transform::isIdentity() const {
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 4; ++j)
            if (m_[i][j] != (i == j ? 1 : 0)) return false;
    return true;
}

}  // namespace glint
