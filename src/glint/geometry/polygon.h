#pragma once
/// Planar polygons, convex or concave, split into triangles by ear clipping, so that they are
/// searched and stored as ordinary triangles.

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "glint/math/vec3.h"

namespace glint {

/// How far a vertex may lie off a polygon's plane, relative to the polygon's size (its largest
/// distance from the centroid of its vertices).
constexpr double kPolygonPlanarity = 1e-3;

/// A polygon's triangles, or why it has none.
struct PolygonTriangulation {
    enum class Problem {
        None,
        SamePosition,      ///< `vertex` is at the position of the earlier `other`.
        ZeroArea,          ///< All vertices on one line (or the area cancels out).
        NonPlanar,         ///< `vertex` lies `offPlane` (relative to the size) off the plane.
        SelfIntersecting,  ///< The edge from `vertex` meets the edge from `other`.
    };
    Problem problem = Problem::None;
    int vertex = -1;  ///< Position in the polygon (0-based) of the vertex at fault.
    int other = -1;
    double offPlane = 0;

    /// Unit Newell normal: the vertices run counter-clockwise seen from its tip.
    Vec3 normal;
    /// Positions in the polygon, each triangle in the polygon's orientation (its face normal
    /// points along `normal`). Collinear vertices are kept as corners of triangles; no
    /// triangle has zero area.
    std::vector<std::array<uint32_t, 3>> triangles;
};

/// Checks that `points` (at least three) form a simple planar polygon of non-zero area, in
/// that order, and triangulates it. Takes O(n^2) time for n points.
PolygonTriangulation triangulatePolygon(std::span<const Vec3> points);

}  // namespace glint
