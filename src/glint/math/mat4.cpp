#include "glint/math/mat4.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

namespace glint {

Mat4 Mat4::translate(double x, double y, double z) {
    Mat4 r;
    r.m[0][3] = x;
    r.m[1][3] = y;
    r.m[2][3] = z;
    return r;
}

Mat4 Mat4::scale(double x, double y, double z) {
    Mat4 r;
    r.m[0][0] = x;
    r.m[1][1] = y;
    r.m[2][2] = z;
    return r;
}

Mat4 Mat4::rotate(double x, double y, double z, double degrees) {
    // Scale by the largest component first: x*x would underflow for an axis like (1e-200, 0, 0).
    double big = std::max({std::abs(x), std::abs(y), std::abs(z)});
    x /= big;
    y /= big;
    z /= big;
    double len = std::sqrt(x * x + y * y + z * z);
    x /= len;
    y /= len;
    z /= len;
    double a = degrees * std::numbers::pi / 180.0;
    double c = std::cos(a), s = std::sin(a), t = 1 - c;
    // Rodrigues' formula: c I + (1 - c) a a^T + s [a]x.
    Mat4 r;
    r.m[0][0] = c + t * x * x;
    r.m[0][1] = t * x * y - s * z;
    r.m[0][2] = t * x * z + s * y;
    r.m[1][0] = t * x * y + s * z;
    r.m[1][1] = c + t * y * y;
    r.m[1][2] = t * y * z - s * x;
    r.m[2][0] = t * x * z - s * y;
    r.m[2][1] = t * y * z + s * x;
    r.m[2][2] = c + t * z * z;
    return r;
}

Mat4 operator*(const Mat4& a, const Mat4& b) {
    Mat4 r;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
            double sum = 0;
            for (int k = 0; k < 4; ++k) sum += a.m[i][k] * b.m[k][j];
            r.m[i][j] = sum;
        }
    return r;
}

Mat4 transpose(const Mat4& a) {
    Mat4 r;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) r.m[i][j] = a.m[j][i];
    return r;
}

std::optional<Mat4> inverse(const Mat4& a) {
    // Gauss-Jordan elimination with partial pivoting.
    double w[4][8];
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
            w[i][j] = a.m[i][j];
            w[i][j + 4] = i == j ? 1.0 : 0.0;
        }
    for (int col = 0; col < 4; ++col) {
        int pivot = col;
        for (int r = col + 1; r < 4; ++r)
            if (std::abs(w[r][col]) > std::abs(w[pivot][col])) pivot = r;
        if (w[pivot][col] == 0 || !std::isfinite(w[pivot][col])) return std::nullopt;
        if (pivot != col) std::swap(w[pivot], w[col]);
        double inv = 1.0 / w[col][col];
        for (double& v : w[col]) v *= inv;
        for (int r = 0; r < 4; ++r) {
            if (r == col || w[r][col] == 0) continue;
            double f = w[r][col];
            for (int j = 0; j < 8; ++j) w[r][j] -= f * w[col][j];
        }
    }
    Mat4 r;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) r.m[i][j] = w[i][j + 4];
    return r;
}

}  // namespace glint
