#pragma once
// Small helpers shared by the unit tests.

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <optional>
#include <set>
#include <string>

#include "glint/io/course/course_loader.h"
#include "glint/math/vec3.h"
#include "glint/scene/material.h"
#include "glint/scene/scene.h"

namespace glint::test {

/// The course-format scene `text`, parsed and prepared (warnings dropped).
inline std::unique_ptr<Scene> preparedScene(const std::string& text) {
    std::vector<Diagnostic> warnings;
    auto scene = parseCourseScene(text, "test.test", warnings);
    scene->prepare();
    return scene;
}

/// Expects every component of `a` within `eps` of `b`.
inline void expectNear(const Vec3& a, const Vec3& b, double eps = 1e-12) {
    EXPECT_NEAR(a.x, b.x, eps);
    EXPECT_NEAR(a.y, b.y, eps);
    EXPECT_NEAR(a.z, b.z, eps);
}

/// The closest hit in a prepared scene of the ray from `origin` along `dir`, with its shading
/// data.
inline std::optional<SurfaceInteraction> shoot(const Scene& scene, const Vec3& origin,
                                               const Vec3& dir) {
    Ray ray{origin, normalize(dir)};
    Hit hit;
    if (!scene.bvh().intersect(ray, hit)) return std::nullopt;
    return scene.primitives.interaction(ray, hit);
}

/// Threads of this process now (its entries in /proc/self/task); -1 where that cannot be read.
inline int processThreads() {
    std::error_code ec;
    int n = 0;
    for (std::filesystem::directory_iterator it("/proc/self/task", ec), end; !ec && it != end;
         it.increment(ec))
        ++n;
    return ec || n == 0 ? -1 : n;
}

/// A material with the given terms; emission black.
inline Material makeMaterial(const Vec3& ambient, const Vec3& diffuse = {},
                             const Vec3& specular = {}, double shininess = 1) {
    Material m;
    m.ambient = ambient;
    m.diffuse = diffuse;
    m.specular = specular;
    m.shininess = shininess;
    return m;
}

/// A fixture giving each test its own empty directory, removed afterwards.
class TempDirTest : public ::testing::Test {
  protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = std::filesystem::temp_directory_path() /
               ("glint-" + std::string(info->test_suite_name()) + "-" + std::to_string(::getpid()) +
                "-" + info->name());
        std::filesystem::remove_all(dir_);
        std::filesystem::create_directories(dir_);
    }
    void TearDown() override { std::filesystem::remove_all(dir_); }

    std::string path(const std::string& name) const { return (dir_ / name).string(); }
    std::set<std::string> entries() const {
        std::set<std::string> names;
        for (const auto& e : std::filesystem::directory_iterator(dir_))
            names.insert(e.path().filename().string());
        return names;
    }

    std::filesystem::path dir_;
};

/// A diffuse sphere on a glossy floor under two lights, seen through a thin lens, with
/// `integrator`: path traced, every sample draws random numbers (lens, lights, bounces). For
/// tests of parts of a frame: give sides that are no multiple of the tile size.
inline void buildLensScene(Scene& scene, int width, int height, const std::string& integrator) {
    scene.width = width;
    scene.height = height;
    scene.maxDepth = 3;
    scene.integrator = integrator;
    CameraSpec camera{{0, 2, 6}, {0, 0.7, 0}, {0, 1, 0}, 45};
    camera.apertureRadius = 0.05;
    scene.camera = camera;
    uint32_t floor =
        scene.addMaterial(makeMaterial({0.02, 0.02, 0.02}, {0.5, 0.5, 0.5}, {0.3, 0.3, 0.3}, 30));
    scene.primitives.addTriangle({-5, 0, -5}, {-5, 0, 5}, {5, 0, 5}, nullptr, floor);
    scene.primitives.addTriangle({-5, 0, -5}, {5, 0, 5}, {5, 0, -5}, nullptr, floor);
    uint32_t red = scene.addMaterial(makeMaterial({0, 0, 0}, {0.8, 0.1, 0.1}, {}, 1));
    scene.primitives.addSphere(Sphere{{0, 1, 0}, 1, {}}, red);
    LightSpec point;
    point.position = {3, 5, 3};
    point.color = {8, 8, 8};
    scene.lights.push_back(point);
    LightSpec sun;
    sun.kind = LightSpec::Kind::Directional;
    sun.direction = normalize(Vec3{1, 1, -1});
    sun.color = {0.3, 0.3, 0.3};
    scene.lights.push_back(sun);
    scene.prepare();
}

}  // namespace glint::test
