#include "glint/geometry/polygon.h"

#include <algorithm>
#include <cmath>

namespace glint {
namespace {

using Problem = PolygonTriangulation::Problem;

/// Orientations with |sin(angle)| below this count as collinear: vertices that are collinear
/// in the scene file stay collinear after rounding and projection.
constexpr double kCollinear = 1e-12;
/// Normals shorter than this (relative to the size squared) mean zero area.
constexpr double kZeroArea = 1e-12;

struct P2 {
    double x, y;
};

/// +1 if a, b, c turn counter-clockwise, -1 clockwise, 0 if (nearly) collinear.
int turn(const P2& a, const P2& b, const P2& c) {
    double ux = b.x - a.x, uy = b.y - a.y, vx = c.x - a.x, vy = c.y - a.y;
    double o = ux * vy - uy * vx;
    // |o| = |u| |v| |sin(angle)|, compared squared (no square roots in the inner loops).
    if (o * o <= kCollinear * kCollinear * (ux * ux + uy * uy) * (vx * vx + vy * vy)) return 0;
    return o > 0 ? 1 : -1;
}

/// `p`, collinear with segment ab, lies on it (ends included).
bool within(const P2& a, const P2& b, const P2& p) {
    return std::min(a.x, b.x) <= p.x && p.x <= std::max(a.x, b.x) && std::min(a.y, b.y) <= p.y &&
           p.y <= std::max(a.y, b.y);
}

/// Closed segments ab and cd share a point.
bool segmentsMeet(const P2& a, const P2& b, const P2& c, const P2& d) {
    int d1 = turn(c, d, a), d2 = turn(c, d, b), d3 = turn(a, b, c), d4 = turn(a, b, d);
    if (d1 * d2 < 0 && d3 * d4 < 0) return true;
    return (d1 == 0 && within(c, d, a)) || (d2 == 0 && within(c, d, b)) ||
           (d3 == 0 && within(a, b, c)) || (d4 == 0 && within(a, b, d));
}

/// `p` lies inside or on the counter-clockwise triangle abc.
bool inTriangle(const P2& a, const P2& b, const P2& c, const P2& p) {
    return turn(a, b, p) >= 0 && turn(b, c, p) >= 0 && turn(c, a, p) >= 0;
}

/// Which two edges of the polygon meet other than at their shared corner, if any: returns the
/// first vertices of the later and the earlier edge, or {-1, -1}.
std::array<int, 2> crossingEdges(const std::vector<P2>& p) {
    const int n = static_cast<int>(p.size());
    for (int j = 1; j < n; ++j) {
        const P2 &c = p[static_cast<size_t>(j)], &d = p[static_cast<size_t>((j + 1) % n)];
        for (int i = 0; i < j; ++i) {
            const P2 &a = p[static_cast<size_t>(i)], &b = p[static_cast<size_t>(i + 1)];
            bool adjacent = i + 1 == j || (i == 0 && j == n - 1);
            if (!adjacent) {
                if (segmentsMeet(a, b, c, d)) return {j, i};
                continue;
            }
            // Neighbours share a corner s; they overlap when they fold back onto each other.
            const P2& s = i + 1 == j ? b : a;
            const P2& u = i + 1 == j ? a : b;
            const P2& v = i + 1 == j ? d : c;
            bool sameWay = (u.x - s.x) * (v.x - s.x) + (u.y - s.y) * (v.y - s.y) > 0;
            if (n > 3 && turn(u, s, v) == 0 && sameWay) return {j, i};
        }
    }
    return {-1, -1};
}

/// Ear clipping of the counter-clockwise simple polygon `p`: repeatedly cuts off a convex
/// corner whose triangle holds no other vertex. Ear flags are cached and recomputed for the
/// two neighbours of each cut (cutting only ever turns other corners into ears, so a stale
/// flag can only miss an ear; a full refresh finds it).
std::vector<std::array<uint32_t, 3>> clipEars(const std::vector<P2>& p) {
    const int n = static_cast<int>(p.size());
    std::vector<int> prev(static_cast<size_t>(n)), next(static_cast<size_t>(n));
    for (int i = 0; i < n; ++i) {
        prev[static_cast<size_t>(i)] = (i + n - 1) % n;
        next[static_cast<size_t>(i)] = (i + 1) % n;
    }
    auto at = [&](int i) -> const P2& { return p[static_cast<size_t>(i)]; };
    auto before = [&](int i) { return prev[static_cast<size_t>(i)]; };
    auto after = [&](int i) { return next[static_cast<size_t>(i)]; };
    auto isEar = [&](int i) {
        int a = before(i), c = after(i);
        if (turn(at(a), at(i), at(c)) <= 0) return false;  // reflex or flat
        for (int j = after(c); j != a; j = after(j))
            if (inTriangle(at(a), at(i), at(c), at(j))) return false;
        return true;
    };
    std::vector<char> ear(static_cast<size_t>(n));
    auto refresh = [&](int start, int count) {
        for (int k = 0, i = start; k < count; ++k, i = after(i))
            ear[static_cast<size_t>(i)] = isEar(i);
    };
    refresh(0, n);

    std::vector<std::array<uint32_t, 3>> triangles;
    triangles.reserve(static_cast<size_t>(n - 2));
    auto emit = [&](int i) {
        triangles.push_back({static_cast<uint32_t>(before(i)), static_cast<uint32_t>(i),
                             static_cast<uint32_t>(after(i))});
    };
    auto findEar = [&](int start, int count) {
        for (int k = 0, i = start; k < count; ++k, i = after(i))
            if (ear[static_cast<size_t>(i)]) return i;
        return -1;
    };
    int cur = 0, remaining = n;
    while (remaining > 3) {
        int e = findEar(cur, remaining);
        if (e < 0) {
            refresh(cur, remaining);
            e = findEar(cur, remaining);
        }
        if (e < 0) {
            // Only rounding can leave no ear: cut the sharpest convex corner, or give up on
            // a remainder with none (its triangles would have no area).
            double best = 0;
            for (int k = 0, i = cur; k < remaining; ++k, i = after(i)) {
                const P2 &a = at(before(i)), &b = at(i), &c = at(after(i));
                double o = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
                if (turn(a, b, c) > 0 && o > best) best = o, e = i;
            }
            if (e < 0) return triangles;
        }
        emit(e);
        int a = before(e), c = after(e);
        next[static_cast<size_t>(a)] = c;
        prev[static_cast<size_t>(c)] = a;
        --remaining;
        ear[static_cast<size_t>(a)] = isEar(a);
        ear[static_cast<size_t>(c)] = isEar(c);
        cur = c;
    }
    if (turn(at(before(cur)), at(cur), at(after(cur))) > 0) emit(cur);
    return triangles;
}

}  // namespace

PolygonTriangulation triangulatePolygon(std::span<const Vec3> points) {
    PolygonTriangulation r;
    const int n = static_cast<int>(points.size());
    auto fail = [&](Problem problem, int vertex, int other = -1) {
        r.problem = problem;
        r.vertex = vertex;
        r.other = other;
        return r;
    };
    for (int j = 1; j < n; ++j)
        for (int i = 0; i < j; ++i)
            if (points[static_cast<size_t>(i)] == points[static_cast<size_t>(j)])
                return fail(Problem::SamePosition, j, i);

    // Everything relative to the centroid, where the numbers are of the polygon's size.
    Vec3 c(0);
    for (const Vec3& p : points) c += p;
    c = c / static_cast<double>(n);
    std::vector<Vec3> q;
    q.reserve(static_cast<size_t>(n));
    double size = 0;
    for (const Vec3& p : points) {
        q.push_back(p - c);
        size = std::max(size, length(q.back()));
    }
    // Newell's normal: twice the vector area, exact for planar polygons whatever their shape.
    Vec3 newell(0);
    for (int i = 0; i < n; ++i) {
        const Vec3 &a = q[static_cast<size_t>(i)], &b = q[static_cast<size_t>((i + 1) % n)];
        newell +=
            Vec3((a.y - b.y) * (a.z + b.z), (a.z - b.z) * (a.x + b.x), (a.x - b.x) * (a.y + b.y));
    }
    double area2 = length(newell);
    if (!(area2 > kZeroArea * size * size)) return fail(Problem::ZeroArea, -1);
    r.normal = newell / area2;
    for (int i = 0; i < n; ++i) {
        double off = std::abs(dot(q[static_cast<size_t>(i)], r.normal)) / size;
        if (off > kPolygonPlanarity && off > r.offPlane) r.offPlane = off, r.vertex = i;
    }
    if (r.vertex >= 0) return fail(Problem::NonPlanar, r.vertex);

    // Into the plane's coordinates: drop the normal's largest axis; keep the polygon
    // counter-clockwise in 2D.
    Vec3 an = abs(r.normal);
    int kz = an.x >= an.y && an.x >= an.z ? 0 : (an.y >= an.z ? 1 : 2);
    int kx = (kz + 1) % 3, ky = (kz + 2) % 3;
    double flip = r.normal[kz] < 0 ? -1 : 1;
    std::vector<P2> p2;
    p2.reserve(static_cast<size_t>(n));
    for (const Vec3& p : q) p2.push_back({p[kx], p[ky] * flip});

    auto [later, earlier] = crossingEdges(p2);
    if (later >= 0) return fail(Problem::SelfIntersecting, later, earlier);
    r.triangles = clipEars(p2);
    return r;
}

}  // namespace glint
