// Per-triangle shading attributes: vertex normals and texture coordinates, stored only for the
// triangles that have them, interpolated at the hit.

#include "glint/geometry/primitives.h"

#include <gtest/gtest.h>

#include "glint/accel/bvh.h"
#include "unit/test_support.h"

namespace glint {
namespace {

using test::expectNear;

/// The closest hit straight down onto z = 0 at (x, y).
SurfaceInteraction hitFromAbove(const Primitives& prims, double x, double y) {
    Bvh bvh;
    bvh.build(prims);
    Ray ray{{x, y, 3}, {0, 0, -1}};
    Hit hit;
    EXPECT_TRUE(bvh.intersect(ray, hit));
    return prims.interaction(ray, hit);
}

const Vec3 kA{0, 0, 0}, kB{2, 0, 0}, kC{0, 2, 0};
const TexCoord kUv[3] = {{0, 0}, {1, 0}, {0, 1}};

TEST(PrimitiveAttributes, TextureCoordinatesAreInterpolatedBarycentrically) {
    Primitives prims;
    ASSERT_TRUE(prims.addTriangle(kA, kB, kC, nullptr, kUv, 3));
    SurfaceInteraction si = hitFromAbove(prims, 0.5, 0.25);
    EXPECT_TRUE(si.hasUv);
    EXPECT_NEAR(si.u, 0.25, 1e-12);
    EXPECT_NEAR(si.v, 0.125, 1e-12);
    EXPECT_EQ(si.material, 3u);
    expectNear(si.n, {0, 0, 1});  // no vertex normals: the face normal
}

TEST(PrimitiveAttributes, NormalsAndCoordinatesTogetherAndApart) {
    Primitives prims;
    const Vec3 tilted[3] = {normalize(Vec3{1, 0, 1}), normalize(Vec3{1, 0, 1}),
                            normalize(Vec3{1, 0, 1})};
    Vec3 shift{10, 0, 0};
    prims.addTriangle(kA, kB, kC, nullptr, 0);                         // flat
    prims.addTriangle(kA + shift, kB + shift, kC + shift, tilted, 0);  // normals
    prims.addTriangle(kA + shift * 2.0, kB + shift * 2.0, kC + shift * 2.0, tilted, kUv, 0);
    prims.addTriangle(kA + shift * 3.0, kB + shift * 3.0, kC + shift * 3.0, nullptr, kUv, 0);
    prims.addTriangle(kA + shift * 4.0, kB + shift * 4.0, kC + shift * 4.0, nullptr, 0);
    EXPECT_EQ(prims.texturedTriangleCount(), 2u);

    SurfaceInteraction flat = hitFromAbove(prims, 0.5, 0.5);
    EXPECT_FALSE(flat.hasUv);
    expectNear(flat.n, {0, 0, 1});
    SurfaceInteraction smooth = hitFromAbove(prims, 10.5, 0.5);
    EXPECT_FALSE(smooth.hasUv);
    expectNear(smooth.n, tilted[0]);
    SurfaceInteraction both = hitFromAbove(prims, 20.5, 0.5);
    EXPECT_TRUE(both.hasUv);
    expectNear(both.n, tilted[0]);
    EXPECT_NEAR(both.u, 0.25, 1e-12);
    SurfaceInteraction uvOnly = hitFromAbove(prims, 30.5, 0.5);
    EXPECT_TRUE(uvOnly.hasUv);
    expectNear(uvOnly.n, {0, 0, 1});
    EXPECT_NEAR(uvOnly.v, 0.25, 1e-12);
    SurfaceInteraction last = hitFromAbove(prims, 40.5, 0.5);
    EXPECT_FALSE(last.hasUv);
    expectNear(last.n, {0, 0, 1});
}

TEST(PrimitiveAttributes, DegenerateTrianglesAreDroppedWithTheirAttributes) {
    Primitives prims;
    EXPECT_FALSE(prims.addTriangle(kA, kA, kC, nullptr, kUv, 0));
    EXPECT_EQ(prims.triangleCount(), 0u);
    EXPECT_EQ(prims.texturedTriangleCount(), 0u);
}

}  // namespace
}  // namespace glint
