#pragma once
// Helpers shared by the scene-format loader tests.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "glint/io/course/course_loader.h"
#include "unit/test_support.h"

namespace glint::test {

/// A valid camera, appended to scenes that are not about the camera.
const std::string kCamera = "camera 0 0 10 0 0 0 0 1 0 45\n";
/// Three lines defining vertices 0, 1, 2 of a unit right triangle in the z = 0 plane.
const std::string kVerts = "vertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n";
/// The same triangle as vertexnormal 0, 1, 2, all with the normal +z.
const std::string kNormalVerts =
    "vertexnormal 0 0 0 0 0 1\nvertexnormal 1 0 0 0 0 1\nvertexnormal 0 1 0 0 0 1\n";

inline std::unique_ptr<Scene> parse(const std::string& text, std::vector<Diagnostic>& warnings) {
    return parseCourseScene(text, "t.test", warnings);
}

/// Parses `body` followed by a camera (so line numbers in `body` are unchanged); no warnings.
inline std::unique_ptr<Scene> parseOk(const std::string& body) {
    std::vector<Diagnostic> warnings;
    auto scene = parse(body + kCamera, warnings);
    EXPECT_TRUE(warnings.empty()) << warnings.front().format("warning");
    return scene;
}

/// The diagnostic of the SceneError that parsing `text` throws.
inline Diagnostic errorOf(const std::string& text) {
    std::vector<Diagnostic> warnings;
    try {
        parse(text, warnings);
    } catch (const SceneError& e) {
        return e.diagnostic();
    }
    ADD_FAILURE() << "no SceneError for:\n" << text;
    return {};
}

inline void expectError(const std::string& text, int line, int column, const std::string& message) {
    Diagnostic d = errorOf(text);
    EXPECT_EQ(d.loc.file, "t.test");
    EXPECT_EQ(d.loc.line, line) << text;
    EXPECT_EQ(d.loc.column, column) << text;
    EXPECT_THAT(d.message, ::testing::HasSubstr(message)) << text;
}

/// Parses `body` + camera and expects exactly one warning.
inline Diagnostic warningOf(const std::string& body, std::unique_ptr<Scene>* sceneOut = nullptr) {
    std::vector<Diagnostic> warnings;
    auto scene = parse(body + kCamera, warnings);
    EXPECT_EQ(warnings.size(), 1u) << body;
    if (sceneOut) *sceneOut = std::move(scene);
    return warnings.empty() ? Diagnostic{} : warnings.front();
}

/// The closest hit of the ray from `origin` along `dir`, with its shading data; prepares the
/// scene first if need be.
inline std::optional<SurfaceInteraction> shoot(Scene& scene, const Vec3& origin, const Vec3& dir) {
    if (!scene.prepared()) scene.prepare();
    return shoot(std::as_const(scene), origin, dir);
}

}  // namespace glint::test
