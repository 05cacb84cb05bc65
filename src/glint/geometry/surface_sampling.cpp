#include "glint/geometry/surface_sampling.h"

#include <cmath>
#include <numbers>

namespace glint {
namespace {

constexpr double kPi = std::numbers::pi;

/// A canonical-space point and normal mapped by `t`, with the canonical density `pdf`
/// converted to world area.
SurfaceSample toWorld(const Transform& t, const Vec3& p, const Vec3& n, double pdf) {
    Vec3 wn = normalize(t.normal(n));
    return {t.point(p), wn, pdf * length(t.transposeVector(wn)) / std::abs(t.determinant())};
}

/// Canonical areas of the parts of shape `s`: side (or faces) and caps.
struct ShapeParts {
    double side = 0, cap0 = 0, cap1 = 0;
    double total() const { return side + cap0 + cap1; }
};
ShapeParts parts(const Shape& s) {
    switch (s.kind) {
        case ShapeKind::Box:
            return {24, 0, 0};
        case ShapeKind::Cylinder:
            return {2 * kPi, kPi, kPi};
        case ShapeKind::Cone: {
            double slant = std::sqrt(1 + (1 - s.k) * (1 - s.k));
            return {kPi * (1 + s.k) * slant, kPi, kPi * s.k * s.k};
        }
        default:
            return {kPi, 0, 0};  // disk
    }
}

/// (x, y) of a point uniform on the disk of `radius`.
std::pair<double, double> diskPoint(Point2 u, double radius) {
    auto [x, y] = sampleUniformDisk(u.x, u.y);
    return {x * radius, y * radius};
}

}  // namespace

SurfaceSample sampleTriangle(const Vec3& a, const Vec3& b, const Vec3& c, Point2 u) {
    auto [b0, b1] = sampleUniformTriangle(u);
    Vec3 cr = cross(b - a, c - a);
    double len = length(cr);
    return {a * b0 + b * b1 + c * (1 - b0 - b1), cr / len, 2 / len};
}

SurfaceSample sampleSphere(const Sphere& s, Point2 u) {
    Vec3 n = sampleUniformSphere(u);
    return toWorld(s.worldFromObject, s.center + n * s.radius, n,
                   1 / (4 * kPi * s.radius * s.radius));
}

double spherePdfArea(const Sphere& s, const Vec3& n) {
    const Transform& t = s.worldFromObject;
    return length(t.transposeVector(n)) / std::abs(t.determinant()) /
           (4 * kPi * s.radius * s.radius);
}

SurfaceSample sampleShape(const Shape& s, Point2 u) {
    const ShapeParts a = parts(s);
    const double pdf = 1 / a.total();
    const Transform& t = s.worldFromCanonical;
    switch (s.kind) {
        case ShapeKind::Box: {
            // u.x picks the face, and what remains of it places the point.
            int face = std::min(static_cast<int>(u.x * 6), 5);
            u.x = u.x * 6 - face;
            int axis = face % 3;
            double sign = face < 3 ? 1 : -1;
            Vec3 p, n;
            double c0 = 2 * u.x - 1, c1 = 2 * u.y - 1;
            if (axis == 0)
                p = {sign, c0, c1}, n = {sign, 0, 0};
            else if (axis == 1)
                p = {c0, sign, c1}, n = {0, sign, 0};
            else
                p = {c0, c1, sign}, n = {0, 0, sign};
            return toWorld(t, p, n, pdf);
        }
        case ShapeKind::Disk: {
            auto [x, y] = diskPoint(u, 1);
            return toWorld(t, {x, y, 0}, {0, 0, 1}, pdf);
        }
        default:
            break;
    }
    // Cylinder and cone: base cap (z = 0), top cap (z = 1) or side, by canonical area, picked
    // by u.y; what remains of u.y places the point.
    double pick = u.y * a.total();
    if (pick < a.cap0) {
        auto [x, y] = diskPoint({u.x, pick / a.cap0}, 1);
        return toWorld(t, {x, y, 0}, {0, 0, -1}, pdf);
    }
    if (pick < a.cap0 + a.cap1) {
        auto [x, y] =
            diskPoint({u.x, (pick - a.cap0) / a.cap1}, s.kind == ShapeKind::Cone ? s.k : 1);
        return toWorld(t, {x, y, 1}, {0, 0, 1}, pdf);
    }
    double phi = 2 * kPi * std::min((pick - a.cap0 - a.cap1) / a.side, 1.0);
    if (s.kind == ShapeKind::Cylinder)
        return toWorld(t, {std::cos(phi), std::sin(phi), u.x}, {std::cos(phi), std::sin(phi), 0},
                       pdf);
    // The cone's side, radius r(z) = 1 + (k - 1) z: its area density in z is proportional to
    // r(z); inverting the cumulative (z + (k - 1) z^2 / 2) / ((1 + k) / 2) gives z.
    double k = s.k, z = u.x;
    if (k != 1) z = (std::sqrt(std::max(0.0, 1 + (k * k - 1) * u.x)) - 1) / (k - 1);
    double r = 1 + (k - 1) * z;
    Vec3 n = normalize(Vec3(std::cos(phi), std::sin(phi), 1 - k));
    return toWorld(t, {r * std::cos(phi), r * std::sin(phi), z}, n, pdf);
}

double shapePdfArea(const Shape& s, const Vec3& n) {
    const Transform& t = s.worldFromCanonical;
    return length(t.transposeVector(n)) / std::abs(t.determinant()) / parts(s).total();
}

double approximateArea(const Sphere& s) {
    return 4 * kPi * s.radius * s.radius *
           std::pow(std::abs(s.worldFromObject.determinant()), 2.0 / 3.0);
}

double approximateArea(const Shape& s) {
    return parts(s).total() * std::pow(std::abs(s.worldFromCanonical.determinant()), 2.0 / 3.0);
}

}  // namespace glint
