// How the core value types print themselves (operator<<): what a failing test or a debug line
// shows for vectors, points, boxes, matrices, transforms, rays, hits and surface interactions.

#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "glint/core/ray.h"
#include "glint/geometry/primitives.h"
#include "glint/math/bbox.h"
#include "glint/math/mat4.h"
#include "glint/math/sampling.h"
#include "glint/math/transform.h"

namespace glint {
namespace {

template <typename T>
std::string print(const T& value) {
    std::ostringstream out;
    out << value;
    return out.str();
}

TEST(Printing, VectorsPointsAndBoxes) {
    EXPECT_EQ(print(Vec3(1, -2.5, 3e-7)), "(1, -2.5, 3e-07)");
    EXPECT_EQ(print(Vec3f(0.5f, 0, 4)), "(0.5, 0, 4)");
    EXPECT_EQ(print(Point2{0.25, 0.75}), "(0.25, 0.75)");
    EXPECT_EQ(print(Bounds3f{Vec3f(-1, 0, 1), Vec3f(2, 3, 4)}), "[(-1, 0, 1) .. (2, 3, 4)]");
    EXPECT_EQ(print(Bounds3f{}), "[empty]");
    // gtest shows the same in its messages.
    EXPECT_EQ(testing::PrintToString(Vec3(1, 2, 3)), "(1, 2, 3)");
}

TEST(Printing, MatricesAndTransforms) {
    EXPECT_EQ(print(Mat4::translate(1, 2, 3)),
              "[[1, 0, 0, 1], [0, 1, 0, 2], [0, 0, 1, 3], [0, 0, 0, 1]]");
    EXPECT_EQ(print(*Transform::fromMatrix(Mat4::scale(2, 3, 4))),
              "Transform[[2, 0, 0, 0], [0, 3, 0, 0], [0, 0, 4, 0]]");
}

TEST(Printing, RaysHitsAndSurfaceInteractions) {
    EXPECT_EQ(print(Ray{{0, 1, 2}, {0, 0, -1}, 0, 5}),
              "Ray{origin (0, 1, 2), dir (0, 0, -1), t [0, 5]}");
    EXPECT_EQ(print(Ray{{0, 0, 0}, {1, 0, 0}}), "Ray{origin (0, 0, 0), dir (1, 0, 0), t [0, inf]}");
    EXPECT_EQ(print(Hit{}), "Hit{none}");
    EXPECT_EQ(print(Hit{1.5f, 12, 0}), "Hit{t 1.5, prim 12}");
    EXPECT_EQ(print(Hit{2, 40, 3}), "Hit{t 2, prim 40, sub 3}");
    SurfaceInteraction si;
    si.p = {1, 2, 3};
    si.n = si.ng = {0, 1, 0};
    si.material = 4;
    EXPECT_EQ(print(si), "SurfaceInteraction{p (1, 2, 3), n (0, 1, 0), ng (0, 1, 0), material 4}");
    si.hasUv = true;
    si.u = 0.5;
    si.v = 0.25;
    EXPECT_EQ(print(si),
              "SurfaceInteraction{p (1, 2, 3), n (0, 1, 0), ng (0, 1, 0), material 4, uv (0.5, "
              "0.25)}");
}

}  // namespace
}  // namespace glint
