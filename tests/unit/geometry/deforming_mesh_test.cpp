// Deforming meshes (geometry/deforming_mesh.h): triangles keyed over the shutter are
// interpolated linearly between keys; the BVH over their swept bounds finds, at any time, the
// same closest hit as testing every interpolated triangle; occlusion agrees; the bounds hold
// every triangle at every time.

#include "glint/geometry/deforming_mesh.h"

#include <gtest/gtest.h>

#include <random>
#include <vector>

namespace glint {
namespace {

using Corners = DeformingMesh::Corners;

Vec3f randomPoint(std::mt19937& rng, float spread) {
    std::uniform_real_distribution<float> u(-spread, spread);
    return {u(rng), u(rng), u(rng)};
}

/// `count` small triangles scattered in a box, each drifting and turning over `keys` keys.
std::vector<std::vector<Corners>> randomKeys(int keys, int count, uint32_t seed) {
    std::mt19937 rng(seed);
    std::vector<std::vector<Corners>> out(static_cast<size_t>(keys));
    for (int i = 0; i < count; ++i) {
        Vec3f centre = randomPoint(rng, 4);
        for (int k = 0; k < keys; ++k) {
            centre = centre + randomPoint(rng, 0.3f);
            out[static_cast<size_t>(k)].push_back({centre + randomPoint(rng, 0.5f),
                                                   centre + randomPoint(rng, 0.5f),
                                                   centre + randomPoint(rng, 0.5f)});
        }
    }
    return out;
}

TEST(DeformingMesh, TrianglesAreTheKeysAtKeyTimesAndInterpolatedLinearlyBetween) {
    const auto keys = randomKeys(3, 5, 1);
    const DeformingMesh mesh(keys);
    ASSERT_EQ(mesh.size(), 5u);
    EXPECT_EQ(mesh.keys(), 3);
    for (uint32_t i = 0; i < 5; ++i) {
        const Triangle open = mesh.at(i, 0), middle = mesh.at(i, 0.5f), close = mesh.at(i, 1);
        EXPECT_EQ(open.v0, keys[0][i][0]);
        EXPECT_EQ(middle.v1, keys[1][i][1]);
        EXPECT_EQ(close.v2, keys[2][i][2]);
        // A quarter of the way: halfway between the first two keys.
        const Triangle quarter = mesh.at(i, 0.25f);
        const Vec3f expected = (keys[0][i][2] + keys[1][i][2]) * 0.5f;
        for (int a = 0; a < 3; ++a) EXPECT_NEAR(quarter.v2[a], expected[a], 1e-5f);
        // Outside the shutter: its ends.
        EXPECT_EQ(mesh.at(i, -1).v0, open.v0);
        EXPECT_EQ(mesh.at(i, 2).v0, close.v0);
    }
}

TEST(DeformingMesh, TheTreeFindsTheClosestHitOfEveryInterpolatedTriangle) {
    const auto keys = randomKeys(4, 400, 2);
    const DeformingMesh mesh(keys);
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> unit(0, 1);
    int hits = 0;
    for (int r = 0; r < 4000; ++r) {
        const float u = unit(rng);
        const Vec3f origin = randomPoint(rng, 8);
        const Vec3f target = randomPoint(rng, 3);
        const TraversalRay ray(origin, target - origin, 0, r % 4 == 0 ? 0.7f : 1e30f);
        Hit expected;
        bool any = false;
        for (uint32_t i = 0; i < mesh.size(); ++i) {
            float t;
            if (intersectTriangle(mesh.at(i, u), ray, t) && closerHit(t, i, expected))
                expected = {t, i}, any = true;
        }
        Hit hit;
        ASSERT_EQ(mesh.intersect(ray, u, hit), any) << "ray " << r;
        ASSERT_EQ(mesh.occluded(ray, u), any) << "ray " << r;
        if (!any) continue;
        ++hits;
        EXPECT_EQ(hit.t, expected.t);
        EXPECT_EQ(hit.primId, expected.primId);
        // A closer hit already found is kept.
        Hit closer{expected.t * 0.5f, 7};
        EXPECT_FALSE(mesh.intersect(ray, u, closer));
        EXPECT_EQ(closer.primId, 7u);
    }
    EXPECT_GT(hits, 500);  // the rays do meet the triangles, often
}

TEST(DeformingMesh, TheBoundsHoldEveryTriangleAtEveryTime) {
    const auto keys = randomKeys(5, 50, 4);
    const DeformingMesh mesh(keys);
    const Bounds3f b = mesh.bounds();
    for (int s = 0; s <= 100; ++s)
        for (uint32_t i = 0; i < mesh.size(); ++i) {
            const Bounds3f t = mesh.at(i, static_cast<float>(s) / 100).bounds();
            for (int a = 0; a < 3; ++a) {
                EXPECT_LE(b.lo[a], t.lo[a]);
                EXPECT_GE(b.hi[a], t.hi[a]);
            }
        }
}

TEST(DeformingMesh, NormalsAreInterpolatedAndKeysMustAgree) {
    std::vector<std::vector<Corners>> vertices = {
        {{Vec3f(0, 0, 0), Vec3f(1, 0, 0), Vec3f(0, 1, 0)}},
        {{Vec3f(0, 0, 1), Vec3f(1, 0, 1), Vec3f(0, 1, 1)}}};
    std::vector<std::vector<Corners>> normals = {
        {{Vec3f(0, 0, 1), Vec3f(0, 0, 1), Vec3f(0, 0, 1)}},
        {{Vec3f(1, 0, 0), Vec3f(1, 0, 0), Vec3f(1, 0, 0)}}};
    const DeformingMesh mesh(vertices, normals);
    ASSERT_TRUE(mesh.hasNormals());
    const Corners half = mesh.normalsAt(0, 0.5f);
    EXPECT_FLOAT_EQ(half[1].x, 0.5f);
    EXPECT_FLOAT_EQ(half[1].z, 0.5f);
    EXPECT_THROW(DeformingMesh({vertices[0]}), std::invalid_argument);
    EXPECT_THROW(DeformingMesh(vertices, {normals[0]}), std::invalid_argument);
    vertices[1].push_back(vertices[1][0]);
    EXPECT_THROW(DeformingMesh{vertices}, std::invalid_argument);
}

}  // namespace
}  // namespace glint
