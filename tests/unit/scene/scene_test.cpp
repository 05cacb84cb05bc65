#include "glint/scene/scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <memory>

#include "glint/core/parallel.h"
#include "glint/math/mat4.h"
#include "glint/math/rng.h"
#include "unit/test_support.h"

namespace glint {
namespace {

TEST(Scene, BackgroundRadianceIsTheEnvironmentMapsWhenThereIsOne) {
    Scene scene;
    scene.background = Background{{0, 0, 1}, {1, 0, 0}};
    test::expectNear(scene.backgroundRadiance({0, 1, 0}), {1, 0, 0});
    test::expectNear(scene.backgroundRadiance({1, 0, 0}), {0.5, 0, 0.5});
    // 1 x 2 texels: up (2, 3, 4), down (5, 6, 7), scaled by 2.
    scene.environment =
        std::make_shared<EnvironmentMap>(1, 2, std::vector<float>{2, 3, 4, 5, 6, 7}, 2);
    test::expectNear(scene.backgroundRadiance({0, 1, 0}), {4, 6, 8});
    test::expectNear(scene.backgroundRadiance({0, -1, 0}), {10, 12, 14});
    scene.environment.reset();
    test::expectNear(scene.backgroundRadiance({0, -1, 0}), {0, 0, 1});
}

/// Random triangles in a unit cube, plus 24 instances of a shared mesh of random triangles:
/// large enough for the build's parallel phases.
std::unique_ptr<Scene> makeScene() {
    auto scene = std::make_unique<Scene>();
    Rng rng(5);
    auto point = [&](double scale) {
        return Vec3(rng.uniform(), rng.uniform(), rng.uniform()) * scale;
    };
    auto addTriangles = [&](Primitives& prims, int n, double scale) {
        for (int i = 0; i < n; ++i) {
            Vec3 a = point(scale);
            prims.addTriangle(a, a + point(0.05), a + point(0.05), nullptr, 0);
        }
    };
    Primitives mesh;
    addTriangles(mesh, 20000, 1);
    uint32_t index = scene->addSharedMesh(std::move(mesh));
    for (int i = 0; i < 24; ++i)
        scene->primitives.addInstance(
            index, *Transform::fromMatrix(Mat4::translate(i % 6 * 1.5, i / 6 * 1.5, -3)));
    addTriangles(scene->primitives, 30000, 9);
    scene->addMaterial(Material{});
    return scene;
}

TEST(Scene, PrepareBuildsTheSameTreesOnAnyNumberOfThreads) {
    auto one = makeScene(), three = makeScene();
    ThreadPool pool1(1), pool3(3);
    one->prepare({&pool1, Isa::Auto});
    three->prepare({&pool3, Isa::Auto});
    const bvh::BvhData &a = one->bvh().data(), &b = three->bvh().data();
    ASSERT_EQ(a.nodes.size(), b.nodes.size());
    EXPECT_EQ(std::memcmp(a.nodes.data(), b.nodes.data(), a.nodes.size() * sizeof(bvh::Node8)), 0);
    EXPECT_EQ(one->sharedBvhBytes(), three->sharedBvhBytes());
    // Hits inside the instances' meshes agree too (their trees are searched there).
    Rng rng(9);
    int hits = 0;
    for (int i = 0; i < 2000; ++i) {
        Vec3 origin(rng.uniform() * 9, rng.uniform() * 6, 5);
        Vec3 dir(rng.uniform() - 0.5, rng.uniform() - 0.5, -1);
        auto p = test::shoot(*one, origin, dir), q = test::shoot(*three, origin, dir);
        ASSERT_EQ(p.has_value(), q.has_value());
        if (p) {
            EXPECT_TRUE(p->p == q->p);
            ++hits;
        }
    }
    EXPECT_GT(hits, 200);
}

TEST(Scene, PrepareUsesTheKernelsAskedFor) {
    for (Isa isa : {Isa::Portable, Isa::Auto}) {
        auto scene = makeScene();
        ThreadPool pool(2);
        scene->prepare({&pool, isa});
        EXPECT_EQ(scene->bvh().kernels(), isa == Isa::Auto ? Bvh::bestIsa() : isa);
    }
}

}  // namespace
}  // namespace glint
