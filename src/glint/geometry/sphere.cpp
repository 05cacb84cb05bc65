#include "glint/geometry/sphere.h"

namespace glint {

ShapeSearch sphereSearch(const Sphere& s) {
    // unitFromWorld = scale(1/r) * translate(-center) * objectFromWorld
    Mat4 objectFromWorld = s.worldFromObject.inverseMatrix();
    Mat4 unit = Mat4::scale(1 / s.radius, 1 / s.radius, 1 / s.radius) *
                Mat4::translate(-s.center.x, -s.center.y, -s.center.z) * objectFromWorld;
    return ShapeSearch::from(unit, ShapeKind::Sphere);
}

}  // namespace glint
