#pragma once
/// 4x4 matrices in double precision, used to compose transforms before they are baked into the
/// scene. Row-major: m[row][col]; points are column vectors, so `a * b` applies b first.

#include <iosfwd>
#include <optional>

namespace glint {

struct Mat4 {
    double m[4][4] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}};

    static Mat4 identity() { return {}; }
    static Mat4 translate(double x, double y, double z);
    static Mat4 scale(double x, double y, double z);
    /// Rotation by `degrees` about the axis (x, y, z), as glRotate. The axis must be non-zero.
    static Mat4 rotate(double x, double y, double z, double degrees);

    bool operator==(const Mat4&) const = default;
};
/// "[[a, b, c, d], [e, f, g, h], ...]", row by row.
std::ostream& operator<<(std::ostream& out, const Mat4& m);

Mat4 operator*(const Mat4& a, const Mat4& b);
Mat4 transpose(const Mat4& a);
/// Inverse of an affine or general matrix; nothing if it is singular.
std::optional<Mat4> inverse(const Mat4& a);

}  // namespace glint
