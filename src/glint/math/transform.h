#pragma once
/// Affine transforms baked for rendering: the matrix and its inverse, in double precision.

#include <iosfwd>

#include "glint/math/bbox.h"
#include "glint/math/mat4.h"
#include "glint/math/vec3.h"

namespace glint {

/// An affine map with its inverse. Named destination-from-source where stored, e.g.
/// `worldFromObject`. Build one with `Transform::fromMatrix`, which rejects singular matrices.
class Transform {
  public:
    Transform() = default;

    /// The transform for an invertible affine matrix; nothing if `m` is singular or not finite.
    static std::optional<Transform> fromMatrix(const Mat4& m);

    Vec3 point(const Vec3& p) const {
        return {m_[0][0] * p.x + m_[0][1] * p.y + m_[0][2] * p.z + m_[0][3],
                m_[1][0] * p.x + m_[1][1] * p.y + m_[1][2] * p.z + m_[1][3],
                m_[2][0] * p.x + m_[2][1] * p.y + m_[2][2] * p.z + m_[2][3]};
    }
    Vec3 vector(const Vec3& v) const {
        return {m_[0][0] * v.x + m_[0][1] * v.y + m_[0][2] * v.z,
                m_[1][0] * v.x + m_[1][1] * v.y + m_[1][2] * v.z,
                m_[2][0] * v.x + m_[2][1] * v.y + m_[2][2] * v.z};
    }
    /// Applies the inverse to a point (e.g. world to object space for `worldFromObject`).
    Vec3 inversePoint(const Vec3& p) const {
        return {inv_[0][0] * p.x + inv_[0][1] * p.y + inv_[0][2] * p.z + inv_[0][3],
                inv_[1][0] * p.x + inv_[1][1] * p.y + inv_[1][2] * p.z + inv_[1][3],
                inv_[2][0] * p.x + inv_[2][1] * p.y + inv_[2][2] * p.z + inv_[2][3]};
    }
    Vec3 inverseVector(const Vec3& v) const {
        return {inv_[0][0] * v.x + inv_[0][1] * v.y + inv_[0][2] * v.z,
                inv_[1][0] * v.x + inv_[1][1] * v.y + inv_[1][2] * v.z,
                inv_[2][0] * v.x + inv_[2][1] * v.y + inv_[2][2] * v.z};
    }
    /// Maps a normal by the inverse transpose of the linear part. Not normalised.
    Vec3 normal(const Vec3& n) const {
        return {inv_[0][0] * n.x + inv_[1][0] * n.y + inv_[2][0] * n.z,
                inv_[0][1] * n.x + inv_[1][1] * n.y + inv_[2][1] * n.z,
                inv_[0][2] * n.x + inv_[1][2] * n.y + inv_[2][2] * n.z};
    }
    /// Applies the transpose of the linear part: |M^T n| for a unit world normal n is the
    /// reciprocal of how much the inverse transpose stretched it.
    Vec3 transposeVector(const Vec3& n) const {
        return {m_[0][0] * n.x + m_[1][0] * n.y + m_[2][0] * n.z,
                m_[0][1] * n.x + m_[1][1] * n.y + m_[2][1] * n.z,
                m_[0][2] * n.x + m_[1][2] * n.y + m_[2][2] * n.z};
    }
    /// Determinant of the linear part: the factor by which it scales volumes (signed).
    double determinant() const {
        return m_[0][0] * (m_[1][1] * m_[2][2] - m_[1][2] * m_[2][1]) -
               m_[0][1] * (m_[1][0] * m_[2][2] - m_[1][2] * m_[2][0]) +
               m_[0][2] * (m_[1][0] * m_[2][1] - m_[1][1] * m_[2][0]);
    }
    /// Tight bounds of the image of the ball of `radius` around `center`: along each axis the
    /// half-extent is radius times the length of that row of the linear part.
    Bounds3f ballBounds(const Vec3& center, double radius) const;

    Transform inverse() const;
    /// The matrices as 4x4 (last row 0 0 0 1).
    Mat4 matrix() const;
    Mat4 inverseMatrix() const;
    bool isIdentity() const;

  private:
    double m_[3][4] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}};
    double inv_[3][4] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}};
};
/// "Transform[[a, b, c, d], [e, f, g, h], [i, j, k, l]]": the matrix's first three rows.
std::ostream& operator<<(std::ostream& out, const Transform& t);

}  // namespace glint
