// Placing meshes: addMesh (world-space triangles) and MeshPlacer (a mesh placed several times
// is stored once and instanced). An instance must shade exactly like the same mesh placed as
// triangles, and must cost the memory of one copy however many there are.

#include "glint/scene/mesh.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "glint/math/mat4.h"
#include "unit/io/course/course_test_support.h"
#include "unit/test_support.h"

namespace glint {
namespace {

using test::expectNear;
using test::shoot;

/// A tent of four triangles over the unit square in z = 0 rising to (0.5, 0.5, 0.4), with
/// vertex normals leaning outwards, texture coordinates, and one triangle with an MTL-style
/// material of its own.
MeshData tent() {
    MeshData m;
    m.name = "tent";
    m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5f, 0.5f, 0.4f}};
    m.normals = {{-0.5f, -0.5f, 0.7f},
                 {0.5f, -0.5f, 0.7f},
                 {0.5f, 0.5f, 0.7f},
                 {-0.5f, 0.5f, 0.7f},
                 {0, 0, 1}};
    for (Vec3f& n : m.normals) n = n / std::sqrt(dot(n, n));
    m.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0.5f, 0.5f}};
    MeshMaterial red;
    red.name = "red";
    red.material.diffuse = Vec3(0.9, 0.1, 0.1);
    m.materials.push_back(red);
    for (uint32_t i = 0; i < 4; ++i) {
        MeshData::Triangle t;
        uint32_t a = i, b = (i + 1) % 4;
        t.corners = {MeshData::Corner{a, a, a}, MeshData::Corner{b, b, b},
                     MeshData::Corner{4, 4, 4}};
        t.material = i == 2 ? 0 : MeshData::kNone;
        m.triangles.push_back(t);
    }
    m.normalTriangles = m.uvTriangles = 4;
    return m;
}

Transform placement(double sx, double sy, double sz) {
    return *Transform::fromMatrix(Mat4::translate(3, -1, 2) * Mat4::rotate(1, 2, 3, 40) *
                                  Mat4::scale(sx, sy, sz));
}

/// Shoots the same rays at `mesh` placed by `where` as triangles and as an instance (of a mesh
/// placed twice) and compares the shading data. Positions differ by the float rounding of
/// the stored vertices (world space for triangles, the mesh's space for instances).
/// Interpolated shading normals agree as closely, under any scale: triangles carry their vertex
/// normals mapped to world space (not renormalised), instances map the interpolated normal.
void expectInstanceMatchesTriangles(const Transform& where) {
    MeshData mesh = tent();
    Material grey;
    grey.diffuse = Vec3(0.5);

    Scene flat;
    addMesh(flat, mesh, where, flat.addMaterial(grey));
    Scene instanced;
    MeshPlacer placer;
    uint32_t greyId = instanced.addMaterial(grey);
    placer.add(mesh, where, greyId);
    placer.add(mesh, *Transform::fromMatrix(Mat4::translate(50, 0, 0)), greyId);
    placer.place(instanced);
    ASSERT_EQ(flat.primitives.instanceCount(), 0u);
    ASSERT_EQ(instanced.primitives.instanceCount(), 2u);
    ASSERT_EQ(instanced.primitives.triangleCount(), 0u);

    // Rays from above at points over the tent, placed.
    int hits = 0;
    for (int i = 0; i < 10; ++i)
        for (int j = 0; j < 10; ++j) {
            Vec3 target = where.point({0.05 + 0.1 * i, 0.05 + 0.1 * j, 0.1});
            Vec3 origin = target + Vec3(0.3, 0.2, 10);
            auto a = shoot(flat, origin, target - origin);
            auto b = shoot(instanced, origin, target - origin);
            ASSERT_EQ(a.has_value(), b.has_value());
            if (!a) continue;
            ++hits;
            expectNear(a->p, b->p, 1e-6);
            expectNear(a->ng, b->ng, 1e-6);
            EXPECT_GT(dot(a->ng, where.normal({0, 0, 1})), 0);  // the tent's front, placed
            expectNear(a->n, b->n, 1e-5);
            ASSERT_TRUE(a->hasUv && b->hasUv);
            EXPECT_NEAR(a->u, b->u, 1e-6);
            EXPECT_NEAR(a->v, b->v, 1e-6);
            expectNear(flat.materials[a->material].diffuse,
                       instanced.materials[b->material].diffuse);
        }
    EXPECT_GT(hits, 50);
}

TEST(MeshPlacer, AnInstanceShadesLikeTheSameMeshPlacedAsTriangles) {
    expectInstanceMatchesTriangles(placement(1.5, 1.5, 1.5));
    expectInstanceMatchesTriangles(placement(2, 0.5, 3));
    expectInstanceMatchesTriangles(placement(-2, 0.5, 3));  // mirrored: the front stays the front
}

TEST(MeshPlacer, AHundredCopiesAreStoredOnce) {
    // A finely divided sheet of 20,000 triangles, placed 100 times.
    MeshData sheet;
    sheet.name = "sheet";
    constexpr uint32_t kSide = 101;
    for (int y = 0; y < static_cast<int>(kSide); ++y)
        for (int x = 0; x < static_cast<int>(kSide); ++x)
            sheet.positions.push_back(Vec3f(Vec3(x / 100.0, y / 100.0, 0.01 * std::sin(x * 0.3))));
    for (uint32_t y = 0; y + 1 < kSide; ++y)
        for (uint32_t x = 0; x + 1 < kSide; ++x) {
            uint32_t a = y * kSide + x, b = a + 1, c = a + kSide + 1, d = a + kSide;
            sheet.triangles.push_back({{MeshData::Corner{a}, {b}, {c}}});
            sheet.triangles.push_back({{MeshData::Corner{a}, {c}, {d}}});
        }
    ASSERT_EQ(sheet.triangles.size(), 20000u);

    auto placeCopies = [&](int copies) {
        auto scene = std::make_unique<Scene>();
        MeshPlacer placer;
        for (int i = 0; i < copies; ++i)
            placer.add(sheet, *Transform::fromMatrix(Mat4::translate(i % 10, i / 10, 0)), 0);
        placer.place(*scene);
        scene->prepare();
        return scene;
    };
    auto one = placeCopies(1), two = placeCopies(2), hundred = placeCopies(100);
    EXPECT_EQ(one->primitives.triangleCount(), 20000u);  // once: plain triangles
    EXPECT_EQ(hundred->primitives.triangleCount(), 0u);
    EXPECT_EQ(hundred->primitives.instanceCount(), 100u);
    EXPECT_EQ(hundred->sharedTriangleCount(), 20000u);  // stored once
    EXPECT_EQ(hundred->primitives.instancedTriangleCount(), 2000000u);
    // Memory: the hundred copies' trees together cost about what one copy's tree does.
    size_t oneBytes = one->bvh().stats().bytes;
    size_t hundredBytes = hundred->bvh().stats().bytes + hundred->sharedBvhBytes();
    EXPECT_EQ(two->sharedBvhBytes(), hundred->sharedBvhBytes());
    EXPECT_LT(hundredBytes, oneBytes + oneBytes / 10);
    // And every copy is there.
    for (int i = 0; i < 100; ++i) {
        Vec3 origin(i % 10 + 0.5, i / 10 + 0.5, 5);
        auto hit = shoot(*hundred, origin, {0, 0, -1});
        ASSERT_TRUE(hit) << "copy " << i;
        EXPECT_NEAR(hit->p.z, 0.01 * std::sin(50 * 0.3), 0.02);
    }
}

TEST(MeshPlacer, AMeshOfOnlyDegenerateTrianglesPlacedTwiceAddsNothing) {
    MeshData line;
    line.name = "line";
    line.positions = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
    line.triangles.push_back({{MeshData::Corner{0}, {1}, {2}}});
    Scene scene;
    MeshPlacer placer;
    placer.add(line, Transform(), 0);
    placer.add(line, *Transform::fromMatrix(Mat4::translate(0, 1, 0)), 0);
    std::vector<MeshPlacement> placed = placer.place(scene);
    ASSERT_EQ(placed.size(), 2u);
    EXPECT_EQ(placed[1].degenerate, 1u);
    EXPECT_EQ(scene.primitives.size(), 0u);
    scene.prepare();
    Hit hit;
    EXPECT_FALSE(scene.bvh().intersect(Ray{{0.5, 0, 5}, {0, 0, -1}}, hit));
}

TEST(MeshPlacer, AnInstancePlacedBeyondTheCoordinateRangeIsAnError) {
    MeshData mesh = tent();
    Scene scene;
    MeshPlacer placer;
    placer.add(mesh, Transform(), 0);
    placer.add(mesh, *Transform::fromMatrix(Mat4::translate(2e18, 0, 0)), 0, {"scene.test", 7, 1},
               "mesh 'tent.obj'");
    try {
        placer.place(scene);
        FAIL() << "no error";
    } catch (const SceneError& e) {
        EXPECT_EQ(e.diagnostic().loc.line, 7);
        EXPECT_NE(e.diagnostic().message.find("mesh 'tent.obj': "), std::string::npos);
        EXPECT_NE(e.diagnostic().message.find("coordinate range"), std::string::npos);
    }
}

}  // namespace
}  // namespace glint
