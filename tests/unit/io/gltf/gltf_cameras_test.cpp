// Choosing one of a glTF file's cameras (GltfOptions::camera, LoadOptions::camera, `glint
// --camera`): by number in the order of the node walk, by camera or node name, none; and the
// errors that list the cameras there are.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <numbers>
#include <string>

#include "glint/io/gltf/gltf_loader.h"
#include "glint/io/registry.h"
#include "unit/io/gltf/gltf_test_support.h"
#include "unit/test_support.h"

namespace glint {
namespace {

using namespace glint::test;
using ::testing::HasSubstr;

/// The triangle under node 0, whose children are met in the order 3, 1, 2: node 3 'side' holds
/// camera 1 'Side' (at (5, 0, 0) looking down -x), node 1 camera 0 'Main' (at (0, 0, 5) looking
/// down -z), node 2 'top' the orthographic camera 2 'Top'.
const std::string kCameras = gltfText(kTriangleViews + R"(,
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
    "cameras": [{"name": "Main", "type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1}},
                {"name": "Side", "type": "perspective", "perspective": {"yfov": 0.5, "znear": 0.1}},
                {"name": "Top", "type": "orthographic",
                 "orthographic": {"xmag": 1, "ymag": 1, "znear": 0.1, "zfar": 10}}],
    "nodes": [{"mesh": 0, "children": [3, 1, 2]},
              {"camera": 0, "translation": [0, 0, 5]},
              {"name": "top", "camera": 2, "translation": [0, 5, 0]},
              {"name": "side", "camera": 1, "translation": [5, 0, 0],
               "rotation": [0, 0.70710678, 0, 0.70710678]}],
    "scenes": [{"nodes": [0]}])",
                                      kTriangle);

const char* kList =
    "the file has 3 cameras: 0 = camera 1 'Side' (node 3 'side'), 1 = camera 0 'Main' (node 1), "
    "2 = camera 2 'Top' (node 2 'top')";

GltfOptions choose(const std::string& text) {
    GltfOptions options;
    options.camera = CameraChoice::parse(text);
    return options;
}

TEST(GltfCameras, ByDefaultTheFirstPerspectiveCameraTheWalkMeets) {
    Model model = parse(kCameras);
    ASSERT_TRUE(model.camera);
    EXPECT_EQ(model.camera->description, "camera 1 'Side' (node 3 'side')");
    expectNear(model.camera->spec.eye, {5, 0, 0}, 1e-9);
    expectNear(normalize(model.camera->spec.center - model.camera->spec.eye), {-1, 0, 0}, 1e-6);
}

TEST(GltfCameras, ANumberCountsCameraNodesInTheOrderOfTheWalk) {
    Model model = parse(kCameras, nullptr, choose("1"));
    ASSERT_TRUE(model.camera);
    EXPECT_EQ(model.camera->description, "camera 0 'Main' (node 1)");
    expectNear(model.camera->spec.eye, {0, 0, 5}, 1e-9);
    EXPECT_NEAR(model.camera->spec.fovyDegrees, 0.8 * 180 / std::numbers::pi, 1e-9);
    model = parse(kCameras, nullptr, choose("0"));
    EXPECT_EQ(model.camera->description, "camera 1 'Side' (node 3 'side')");
}

TEST(GltfCameras, ANameIsTheCamerasOrItsNodes) {
    Model model = parse(kCameras, nullptr, choose("Main"));
    ASSERT_TRUE(model.camera);
    EXPECT_EQ(model.camera->description, "camera 0 'Main' (node 1)");
    model = parse(kCameras, nullptr, choose("side"));  // the node's name
    ASSERT_TRUE(model.camera);
    EXPECT_EQ(model.camera->description, "camera 1 'Side' (node 3 'side')");
}

TEST(GltfCameras, NoneIgnoresTheFilesCameras) {
    std::vector<Diagnostic> warnings;
    Model model = parse(kCameras, &warnings, choose("none"));
    EXPECT_FALSE(model.camera);
    EXPECT_TRUE(warnings.empty());  // not even about the orthographic one
}

TEST(GltfCameras, AnUnknownChoiceIsAnErrorListingTheCameras) {
    EXPECT_EQ(errorParsing(kCameras, choose("3")).message,
              std::string("there is no camera 3 (cameras are numbered from 0 in the order of the "
                          "node tree): ") +
                  kList);
    EXPECT_EQ(errorParsing(kCameras, choose("Front")).message,
              std::string("no camera or camera node is named 'Front': ") + kList);
    EXPECT_EQ(errorParsing(kCameras, choose("2")).message,
              "camera 2: camera 2 'Top' (node 2 'top') is orthographic, and Glint has "
              "perspective cameras only");
    EXPECT_EQ(errorParsing(kCameras, choose("Top")).message,
              "camera 'Top': camera 2 'Top' (node 2 'top') is orthographic, and Glint has "
              "perspective cameras only");
    EXPECT_EQ(errorParsing(gltfText(kTriangleScene, kTriangle), choose("0")).message,
              "there is no camera 0 (cameras are numbered from 0 in the order of the node "
              "tree): the file has no cameras");
}

class CameraChoiceFile : public test::TempDirTest {};

TEST_F(CameraChoiceFile, TheRegistryPassesTheChoiceAndFramesWithoutACamera) {
    std::ofstream(path("cams.gltf")) << kCameras;
    std::vector<Diagnostic> warnings;
    LoadOptions options;
    options.look = ModelLook::classic();  // its note and floor are what this checks
    options.camera = CameraChoice::parse("Main");
    ModelScene m = loadSceneFile(path("cams.gltf"), warnings, options);
    ASSERT_TRUE(m.scene->camera);
    expectNear(m.scene->camera->eye, {0, 0, 5}, 1e-9);
    EXPECT_THAT(m.note, HasSubstr("has no lights"));
    EXPECT_THAT(m.note, HasSubstr("camera 0 'Main' (node 1)"));

    options.camera = CameraChoice::parse("none");
    m = loadSceneFile(path("cams.gltf"), warnings, options);
    EXPECT_THAT(m.note, HasSubstr("cams.gltf has no camera or lights: framing it with a camera"));
    EXPECT_EQ(m.scene->primitives.planeCount(), 1u);  // Glint's floor

    // A model format without cameras: naming one is an error; none is what it has anyway.
    std::ofstream(path("tri.obj")) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    options.camera = CameraChoice::parse("0");
    try {
        loadSceneFile(path("tri.obj"), warnings, options);
        ADD_FAILURE() << "no error";
    } catch (const SceneError& e) {
        EXPECT_EQ(e.diagnostic().message, "there is no camera 0: OBJ files have no cameras");
    }
    options.camera = CameraChoice::parse("none");
    EXPECT_NO_THROW(loadSceneFile(path("tri.obj"), warnings, options));

    // A scene file has its own camera.
    std::ofstream(path("s.test")) << "camera 0 0 5 0 0 0 0 1 0 45\nsphere 0 0 0 1\n";
    options.camera = CameraChoice::parse("1");
    try {
        loadSceneFile(path("s.test"), warnings, options);
        ADD_FAILURE() << "no error";
    } catch (const SceneError& e) {
        EXPECT_EQ(e.diagnostic().message,
                  "a CSE167x scene has the camera its commands define: choosing one of a "
                  "file's cameras (--camera) is for model files");
    }
}

}  // namespace
}  // namespace glint
