// An environment map through the CLI: `environment FILE scale` in a scene lights the camera's
// view (rays that miss see it), upright and scaled.

#include <gtest/gtest.h>

#include <string>

#include "cli/cli_support.h"
#include "glint/io/image/exr.h"
#include "glint/io/image/image_io.h"

namespace glint::test {
namespace {

TEST(CliEnvironment, CameraRaysSeeTheMapUprightAndScaled) {
    std::string dir = freshDir("environment");
    // 4 x 64 texels: the upper half (0.5, 1, 2), the lower half (4, 2, 1).
    Film map(4, 64);
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 4; ++x) map.at(x, y) = y < 32 ? Vec3(0.5, 1, 2) : Vec3(4, 2, 1);
    writeFile(dir + "/maps/sky.exr", encodeExr(map));
    writeFile(dir + "/scene.test",
              "size 2 2\ncamera 0 0 0 0 0 -1 0 1 0 60\nenvironment maps/sky.exr 2\n");
    CommandResult r = runGlint("-q scene.test -o out.exr", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(r.err, "");
    Film out = readExr(dir + "/out.exr");
    ASSERT_EQ(out.width(), 2);
    for (int x = 0; x < 2; ++x) {
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(out.at(x, 0)[c], Vec3(1, 2, 4)[c], 1e-6) << x;  // above the horizon
            EXPECT_NEAR(out.at(x, 1)[c], Vec3(8, 4, 2)[c], 1e-6) << x;  // below it
        }
    }
}

}  // namespace
}  // namespace glint::test
