#pragma once
/// Points drawn on the surfaces of primitives, for lights made of emissive geometry.
///
/// Triangles are sampled uniformly by area. Spheres and the other shapes are sampled
/// uniformly over their canonical surface (shapes.h, sphere.h) and mapped to the world by
/// their transform, which may stretch them unevenly: the density over world area at a point
/// is then the canonical density divided by the transform's area scale there,
///
///   dA_world / dA_canonical = |det M| / |M^T n|,
///
/// M the linear part of the transform, n the unit world normal at the point (the inverse
/// transpose maps normals: n ~ M^-T n_canonical). So the density at any surface point,
/// whether drawn here or found by a ray, needs only its world normal.

#include "glint/geometry/shapes.h"
#include "glint/geometry/sphere.h"
#include "glint/math/sampling.h"
#include "glint/math/transform.h"

namespace glint {

/// A point on a surface and its density.
struct SurfaceSample {
    Vec3 p;              ///< World space.
    Vec3 n;              ///< Unit geometric normal (outward for closed shapes).
    double pdfArea = 0;  ///< Density over world area, 1 / m^2.
};

/// Uniform over the triangle a, b, c.
SurfaceSample sampleTriangle(const Vec3& a, const Vec3& b, const Vec3& c, Point2 u);

/// Over the transformed sphere `s`, uniform on its object-space sphere.
SurfaceSample sampleSphere(const Sphere& s, Point2 u);
/// The density sampleSphere gives the surface point whose unit world normal is `n`.
double spherePdfArea(const Sphere& s, const Vec3& n);

/// Over the box, cylinder, cone or disk `s`, uniform on its canonical surface (the closed
/// shapes' caps included); one coordinate of `u` also picks the face or part.
SurfaceSample sampleShape(const Shape& s, Point2 u);
/// The density sampleShape gives the surface point whose unit world normal is `n`.
double shapePdfArea(const Shape& s, const Vec3& n);

/// World-space area of the transformed sphere and shape, approximated (exact for similarity
/// transforms): their canonical area times |det M|^(2/3). For choosing lights by power.
double approximateArea(const Sphere& s);
double approximateArea(const Shape& s);

}  // namespace glint
