#pragma once
/// The float search record of a bounded shape other than a triangle: the shape's kind and the
/// map from world space to its canonical space, where every shape of a kind has the same size
/// and place (the unit sphere, the box [-1, 1]^3, ...: see shapes.h). Everything about one
/// shape, the transform in effect and its own size and placement, is folded into this one map.
///
/// The ray's direction is mapped but not renormalised, so a ray parameter t names the same
/// point in world and canonical space: a search returns the world ray's t directly.

#include <cmath>
#include <cstdint>

#include "glint/core/ray.h"
#include "glint/math/bits.h"
#include "glint/math/mat4.h"

namespace glint {

/// Kinds of bounded shapes with a canonical space. Triangles are separate (they are searched
/// four at a time); planes are unbounded (plane.h).
enum class ShapeKind : uint32_t {
    Sphere,    ///< x^2 + y^2 + z^2 <= 1
    Box,       ///< [-1, 1]^3
    Cylinder,  ///< x^2 + y^2 <= 1, 0 <= z <= 1
    Cone,      ///< sqrt(x^2 + y^2) <= 1 + (k - 1) z, 0 <= z <= 1, k in [0, 1]
    Disk,      ///< z = 0, x^2 + y^2 <= 1
    /// A placed shared mesh: "canonical" space is the mesh's own space, searched by the mesh's
    /// BVH (accel/), not by intersectShape(). The record's mesh() names the mesh.
    Instance,
};

struct ShapeSearch {
    float m[3][4];  ///< canonicalFromWorld: rows of a 3x4 matrix.
    ShapeKind kind = ShapeKind::Sphere;
    /// Cone: its radius at z = 1 (it is 1 at z = 0). Instance: the mesh index (see mesh()).
    float k = 1;

    /// The search record for `canonicalFromWorld` (rounded to float).
    static ShapeSearch from(const Mat4& canonicalFromWorld, ShapeKind kind, double k = 1) {
        ShapeSearch s{};
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 4; ++j) s.m[i][j] = static_cast<float>(canonicalFromWorld.m[i][j]);
        s.kind = kind;
        s.k = static_cast<float>(k);
        return s;
    }

    /// The search record of an instance of shared mesh `mesh` placed by the inverse of
    /// `objectFromWorld`.
    static ShapeSearch instance(const Mat4& objectFromWorld, uint32_t mesh) {
        ShapeSearch s = from(objectFromWorld, ShapeKind::Instance);
        s.k = bitCast<float>(mesh);
        return s;
    }
    /// The shared mesh an Instance record places (kept in the bits of `k`, which instances do
    /// not use otherwise).
    uint32_t mesh() const { return bitCast<uint32_t>(k); }

    /// The ray's origin and (unnormalised) direction in canonical space.
    void map(const TraversalRay& ray, Vec3f& o, Vec3f& d) const {
        o = {m[0][0] * ray.origin.x + m[0][1] * ray.origin.y + m[0][2] * ray.origin.z + m[0][3],
             m[1][0] * ray.origin.x + m[1][1] * ray.origin.y + m[1][2] * ray.origin.z + m[1][3],
             m[2][0] * ray.origin.x + m[2][1] * ray.origin.y + m[2][2] * ray.origin.z + m[2][3]};
        d = {m[0][0] * ray.dir.x + m[0][1] * ray.dir.y + m[0][2] * ray.dir.z,
             m[1][0] * ray.dir.x + m[1][1] * ray.dir.y + m[1][2] * ray.dir.z,
             m[2][0] * ray.dir.x + m[2][1] * ray.dir.y + m[2][2] * ray.dir.z};
    }

    /// The largest magnitude in the map (NaN if any entry is NaN): large entries mean a shape
    /// so thin that the float search would overflow.
    float largestEntry() const {
        float r = 0;
        for (const auto& row : m)
            for (float v : row) r = std::isnan(v) || std::abs(v) > r ? std::abs(v) : r;
        return r;
    }
};

}  // namespace glint
