#include "glint/geometry/shapes.h"

namespace glint {
namespace {

/// A matrix with columns x, y, z and translation t.
Mat4 columns(const Vec3& x, const Vec3& y, const Vec3& z, const Vec3& t) {
    Mat4 m;
    for (int r = 0; r < 3; ++r) {
        m.m[r][0] = x[r];
        m.m[r][1] = y[r];
        m.m[r][2] = z[r];
        m.m[r][3] = t[r];
    }
    return m;
}

/// `v` (non-zero) at unit length, scaled first so that its length cannot overflow or underflow.
Vec3 direction(const Vec3& v) { return normalize(v / maxComponent(abs(v))); }

/// Two unit vectors completing the unit vector `n` to an orthonormal basis.
void perpendiculars(const Vec3& n, Vec3& u, Vec3& v) {
    Vec3 helper = std::abs(n.x) < 0.6 ? Vec3(1, 0, 0) : Vec3(0, 1, 0);
    u = normalize(cross(n, helper));
    v = cross(n, u);
}

/// Placement of a shape whose canonical axis runs from `base` (z = 0) to `tip` (z = 1), with
/// canonical radius 1 scaled to `radius`.
Mat4 axial(const Vec3& base, const Vec3& tip, double radius) {
    Vec3 axis = tip - base, u, v;
    perpendiculars(direction(axis), u, v);
    return columns(u * radius, v * radius, axis, base);
}

}  // namespace

Mat4 boxPlacement(const Vec3& corner0, const Vec3& corner1) {
    Vec3 c = (corner0 + corner1) * 0.5, h = abs(corner1 - corner0) * 0.5;
    return Mat4::translate(c.x, c.y, c.z) * Mat4::scale(h.x, h.y, h.z);
}

Mat4 cylinderPlacement(const Vec3& end0, const Vec3& end1, double radius) {
    return axial(end0, end1, radius);
}

Mat4 conePlacement(const Vec3& end0, double radius0, const Vec3& end1, double radius1, double& k) {
    if (radius1 > radius0) {
        k = radius0 / radius1;
        return axial(end1, end0, radius1);
    }
    k = radius1 / radius0;
    return axial(end0, end1, radius0);
}

Mat4 diskPlacement(const Vec3& center, const Vec3& normal, double radius) {
    Vec3 n = direction(normal), u, v;
    perpendiculars(n, u, v);
    return columns(u * radius, v * radius, n * radius, center);
}

Bounds3f Shape::bounds() const {
    const Mat4 w = worldFromCanonical.matrix();
    Vec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
    auto add = [&](const Vec3& center, const Vec3& half) {
        lo = min(lo, center - half);
        hi = max(hi, center + half);
    };
    auto at = [&](double z) {
        return Vec3(w.m[0][2] * z + w.m[0][3], w.m[1][2] * z + w.m[1][3],
                    w.m[2][2] * z + w.m[2][3]);
    };
    // The ellipse that the canonical circle of radius r at height z becomes: along each axis
    // its half extent is r times the length of that row's x and y entries.
    auto circle = [&](double z, double r) {
        Vec3 half;
        for (int a = 0; a < 3; ++a) half[a] = r * std::hypot(w.m[a][0], w.m[a][1]);
        add(at(z), half);
    };
    switch (kind) {
        case ShapeKind::Box: {
            Vec3 half;
            for (int a = 0; a < 3; ++a)
                half[a] = std::abs(w.m[a][0]) + std::abs(w.m[a][1]) + std::abs(w.m[a][2]);
            add(at(0), half);
            break;
        }
        case ShapeKind::Cylinder:
        case ShapeKind::Cone:
            circle(0, 1);
            circle(1, kind == ShapeKind::Cone ? k : 1);
            break;
        case ShapeKind::Disk:
        case ShapeKind::Sphere:    // not a Shape; bounds of the unit disk as a fallback
        case ShapeKind::Instance:  // not a Shape either (Primitives::addInstance)
            circle(0, 1);
            break;
    }
    return paddedSearchBounds(lo, hi);
}

Bounds3f paddedSearchBounds(const Vec3& lo, const Vec3& hi) {
    // 16 float ulps of the size and coordinates.
    constexpr double kBoundsPadding = 0x1p-20;
    double size = maxComponent(hi - lo) + std::max(maxComponent(abs(lo)), maxComponent(abs(hi)));
    double pad = kBoundsPadding * size;
    return Bounds3f::enclosing(lo - Vec3(pad), hi + Vec3(pad));
}

double refineShapeHit(const Shape& s, const Ray& ray, float tFloat, Vec3& local) {
    Vec3 o = s.worldFromCanonical.inversePoint(ray.origin);
    Vec3 d = s.worldFromCanonical.inverseVector(ray.dir);
    double t = tFloat;
    if (s.kind == ShapeKind::Disk) {
        if (d.z != 0) t = -o.z / d.z;
    } else {
        detail::Span<double> span = detail::solidSpan(s.kind, s.k, o, d);
        // The bound nearest the float hit: entry or exit (a ray from inside).
        if (span.hit())
            t = std::abs(span.enter - t) <= std::abs(span.exit - t) ? span.enter : span.exit;
    }
    local = o + d * t;
    return t;
}

Vec3 canonicalNormal(ShapeKind kind, double k, const Vec3& p) {
    switch (kind) {
        case ShapeKind::Sphere:
            return normalize(p);
        case ShapeKind::Box: {
            Vec3 a = abs(p);
            int axis = a.x >= a.y && a.x >= a.z ? 0 : (a.y >= a.z ? 1 : 2);
            Vec3 n(0);
            n[axis] = p[axis] >= 0 ? 1 : -1;
            return n;
        }
        case ShapeKind::Cylinder:
        case ShapeKind::Cone: {
            double rho = std::hypot(p.x, p.y);
            double slope = kind == ShapeKind::Cone ? 1 - k : 0;
            // Distances (canonical units) to the side, the bottom cap and the top cap.
            double side = std::abs(rho - (1 - slope * p.z)) / std::sqrt(1 + slope * slope);
            double bottom = std::abs(p.z);
            double top = kind == ShapeKind::Cone && k == 0 ? kInfinity : std::abs(p.z - 1);
            if (bottom <= side && bottom <= top) return {0, 0, -1};
            if (top <= side || !(rho > 0)) return {0, 0, 1};  // the apex has no side normal
            return normalize(Vec3(p.x / rho, p.y / rho, slope));
        }
        case ShapeKind::Disk:
        case ShapeKind::Instance:
            break;
    }
    return {0, 0, 1};
}

}  // namespace glint
