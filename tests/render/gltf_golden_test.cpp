// Golden image of a glTF scene: tests/data/gltf/scene.glb (a textured box placed by two nodes
// sharing one mesh, a smooth metal ball, a ground, the file's camera and its point and
// directional lights) loaded as `glint scene.glb --size 160x90 --integrator whitted` loads it (the
// classic look), rendered and compared
// with the image Glint made when glTF input was accepted (tests/data/gltf/scene.png,
// regenerated only deliberately with tests/data/gltf/regenerate.sh). A few pixels one level off
// are tolerated for floating-point differences on another CPU.

#include <gtest/gtest.h>

#include <string>

#include "glint/io/image/image_diff.h"
#include "glint/io/image/image_io.h"
#include "glint/io/registry.h"
#include "glint/render/renderer.h"
#include "render/accepted_image.h"

namespace glint {
namespace {

TEST(GltfGolden, SceneMatchesItsAcceptedImage) {
    const std::string dir = std::string(GLINT_TEST_DATA_DIR) + "/gltf/";
    std::vector<Diagnostic> warnings;
    ModelScene m = loadModelScene(dir + "scene.glb", warnings, 160, 90, {}, ModelLook::classic());
    EXPECT_TRUE(warnings.empty()) << warnings.front().format("warning");
    EXPECT_EQ(m.note, "");  // the file's camera and lights: nothing assumed
    Scene& scene = *m.scene;
    scene.prepare();
    // The box is placed by two nodes: stored once, with its image texture once.
    EXPECT_EQ(scene.primitives.instanceCount(), 2u);
    EXPECT_EQ(scene.textures.size(), 1u);
    test::expectAcceptedImage(toImage8(render(scene, RenderOptions{}).film), dir + "scene.png",
                              "gltf scene");
}

}  // namespace
}  // namespace glint
