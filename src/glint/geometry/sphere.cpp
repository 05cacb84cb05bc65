#include "glint/geometry/sphere.h"

namespace glint {

SphereSearch SphereSearch::from(const Sphere& s) {
    // unitFromWorld = scale(1/r) * translate(-center) * objectFromWorld
    Mat4 objectFromWorld = s.worldFromObject.inverseMatrix();
    Mat4 unit = Mat4::scale(1 / s.radius, 1 / s.radius, 1 / s.radius) *
                Mat4::translate(-s.center.x, -s.center.y, -s.center.z) * objectFromWorld;
    SphereSearch r{};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 4; ++j) r.m[i][j] = static_cast<float>(unit.m[i][j]);
    return r;
}

}  // namespace glint
