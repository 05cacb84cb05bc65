// Golden image of meshes and textures: tests/data/meshes/textured-scene.test (OBJ meshes with
// an MTL texture that repeats, a scene texture that clamps, vertex normals and a checker
// floor) rendered at its 160x90 and compared with the image Glint made when the feature was
// accepted (tests/data/meshes/textured-scene.png, regenerated only deliberately with
// tests/data/meshes/regenerate.sh). Renders are deterministic; a few pixels one level off are
// tolerated for floating-point differences on another CPU.

#include <gtest/gtest.h>

#include <string>

#include "glint/io/course/course_loader.h"
#include "glint/io/image/image_io.h"
#include "glint/io/image/image_diff.h"
#include "glint/render/renderer.h"
#include "render/accepted_image.h"

namespace glint {
namespace {

TEST(MeshGolden, TexturedSceneMatchesItsAcceptedImage) {
    const std::string dir = std::string(GLINT_TEST_DATA_DIR) + "/meshes/";
    std::vector<Diagnostic> warnings;
    auto scene = loadCourseScene(dir + "textured-scene.test", warnings);
    EXPECT_TRUE(warnings.empty()) << warnings.front().format("warning");
    scene->prepare();
    EXPECT_EQ(scene->textures.size(), 3u);  // the floor's checker and two images
    test::expectAcceptedImage(toImage8(render(*scene, RenderOptions{}).film),
                              dir + "textured-scene.png", "textured-scene");
}

}  // namespace
}  // namespace glint
