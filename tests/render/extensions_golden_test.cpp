// Golden images of the extension example scenes (scenes/*.test, shown in
// docs/scene-format.md): each rendered small, with seed 0, and compared with the image Glint
// made when the feature was accepted (tests/data/extensions/, regenerated only deliberately,
// with `tests/data/extensions/regenerate.sh`). Renders are deterministic, so differences come
// only from a change in behaviour, or from floating-point differences on another CPU: a few
// pixels one level off are tolerated, no more.

#include <gtest/gtest.h>

#include <string>

#include "glint/io/course/course_loader.h"
#include "glint/io/image/image_diff.h"
#include "glint/io/image/image_io.h"
#include "glint/render/renderer.h"
#include "render/accepted_image.h"

namespace glint {
namespace {

constexpr int kWidth = 160, kHeight = 90;

class ExtensionScene : public testing::TestWithParam<const char*> {};

TEST_P(ExtensionScene, MatchesItsAcceptedImage) {
    std::string name = GetParam();
    std::vector<Diagnostic> warnings;
    auto scene = loadCourseScene(std::string(GLINT_SCENES_DIR) + "/" + name + ".test", warnings);
    EXPECT_TRUE(warnings.empty());
    scene->width = kWidth;
    scene->height = kHeight;
    scene->prepare();
    RenderOptions o;
    o.spp = scene->spp > 0 ? scene->spp : 1;
    RenderResult result = render(*scene, o);
    test::expectAcceptedImage(toImage8(result.film),
                              std::string(GLINT_TEST_DATA_DIR) + "/extensions/" + name + ".png",
                              name);
}

INSTANTIATE_TEST_SUITE_P(Scenes, ExtensionScene,
                         testing::Values("shapes", "glass", "arealight", "dof", "antialias",
                                         "cornell"),
                         [](const auto& p) { return std::string(p.param); });

}  // namespace
}  // namespace glint
