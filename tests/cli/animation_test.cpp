// Time on the command line (docs/animation.md): --frame, --time-at, --fps, --animation and
// sequences with --frames, for a model file and for a scene whose mesh line loads an animated
// glTF file. The animated asset is written here: a quad that slides along x and turns.

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "cli/cli_support.h"
#include "unit/io/gltf/gltf_asset_builder.h"

namespace glint::test {
namespace {

namespace fs = std::filesystem;

/// A unit quad facing +z, placed by node 0: sliding from x = -1 to 1 and turning a quarter
/// about y over animation 0 'Slide' (2 s), or holding `still` (node members such as
/// "\"translation\": [0, 0, 0]") without an animation.
std::string quad(const std::string& still = "") {
    GltfAsset a;
    int position = a.floats({-0.5f, 0, 0, 0.5f, 0, 0, 0.5f, 1, 0, -0.5f, 1, 0}, "VEC3");
    int indices = a.integers({0, 1, 2, 0, 2, 3}, GltfAsset::kUshort, "SCALAR");
    int times = a.floats({0, 2}, "SCALAR");
    int moves = a.floats({-1, 0, 0, 1, 0, 0}, "VEC3");
    int turns = a.floats({0, 0, 0, 1, 0, 0.70710678f, 0, 0.70710678f}, "VEC4");
    const std::string mesh = R"("meshes": [{"primitives": [{"attributes": {"POSITION": )" +
                             std::to_string(position) + R"(}, "indices": )" +
                             std::to_string(indices) + "}]}]";
    if (!still.empty()) return a.text(mesh + R"(, "nodes": [{"mesh": 0, )" + still + "}]");
    return a.text(mesh + R"(, "nodes": [{"mesh": 0}], "animations": [{"name": "Slide",
        "samplers": [{"input": )" +
                  std::to_string(times) + R"(, "output": )" + std::to_string(moves) +
                  R"(}, {"input": )" + std::to_string(times) + R"(, "output": )" +
                  std::to_string(turns) + R"(}],
        "channels": [{"sampler": 0, "target": {"node": 0, "path": "translation"}},
                     {"sampler": 1, "target": {"node": 0, "path": "rotation"}}]}])");
}

/// A directory holding anim.gltf (the animated quad).
std::string animatedDir(const std::string& name) {
    std::string dir = freshDir(name);
    writeFile(dir + "/anim.gltf", quad());
    return dir;
}

const std::string kSmall = " --size 40x30 --spp 2 -t 2 -q";

TEST(CliAnimation, ASequenceWritesAFilePerFrameEqualToEachFrameRenderedAlone) {
    std::string dir = animatedDir("anim-sequence");
    CommandResult r = runGlint("anim.gltf --frames 0:48:24 -o f_%02d.png" + kSmall, dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    for (const char* f : {"f_00.png", "f_24.png", "f_48.png"})
        EXPECT_TRUE(fs::exists(dir + "/" + f)) << f;
    EXPECT_FALSE(fs::exists(dir + "/f_12.png"));
    // Each frame is the one rendered on its own: same camera (framed for the whole
    // animation), same pose.
    r = runGlint("anim.gltf --frame 24 -o alone.png" + kSmall, dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(readBytes(dir + "/alone.png"), readBytes(dir + "/f_24.png"));
    EXPECT_NE(readBytes(dir + "/f_00.png"), readBytes(dir + "/f_24.png"));
    // --time-at is in the file's seconds, --frame in frames of --fps.
    r = runGlint("anim.gltf --time-at 1 -o t.png" + kSmall, dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(readBytes(dir + "/t.png"), readBytes(dir + "/f_24.png"));
    r = runGlint("anim.gltf --frame 10 --fps 10 -o fps.png" + kSmall, dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(readBytes(dir + "/fps.png"), readBytes(dir + "/f_24.png"));
    // Blender's pattern: a run of #s.
    r = runGlint("anim.gltf --frames 3:3 -o b_####.png" + kSmall, dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(fs::exists(dir + "/b_0003.png"));
}

TEST(CliAnimation, AnAnimatedFrameEqualsTheStillFileHoldingItsValues) {
    std::string dir = animatedDir("anim-still");
    // At 0.5 s: a quarter of the way, x = -0.5, and an eighth of a turn about y.
    writeFile(dir + "/still.gltf",
              quad(R"("translation": [-0.5, 0, 0], "rotation": [0, 0.19509032, 0, 0.98078528])"));
    // A camera of its own and no ground: nothing is framed by the model's extent.
    const std::string view = " --camera orbit:20,70,4,0,0.5,0 --ground none" + kSmall;
    CommandResult r = runGlint("anim.gltf --time-at 0.5 -o a.png" + view, dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    r = runGlint("still.gltf -o s.png" + view, dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(readBytes(dir + "/a.png"), readBytes(dir + "/s.png"));
}

TEST(CliAnimation, TheNoteSaysWhatIsPlayed) {
    std::string dir = animatedDir("anim-note");
    CommandResult r = runGlint("anim.gltf --size 40x30 --spp 1 -t 1", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(contains(r.err,
                         "it has 1 animation, not played (--frame N or --time-at SECONDS "
                         "plays it)"))
        << r.err;
    r = runGlint("anim.gltf --size 40x30 --spp 1 -t 1 --frame 6", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(contains(r.err,
                         "posed by animation 0 'Slide' at 0.25 s, framed for the whole "
                         "animation"))
        << r.err;
    r = runGlint("anim.gltf --check", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(contains(r.out,
                         "animations (1):\n  0  'Slide'  0 to 2 s (frames 0 to 48 at 24 "
                         "fps), 2 channels\n"))
        << r.out;
    r = runGlint("anim.gltf --size 40x30 --spp 1 -t 1 --frames 1:3 -o s%d.png", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(contains(r.err, "glint: frame 1 (1 of 3)")) << r.err;
    EXPECT_TRUE(contains(r.err, "glint: frame 3 (3 of 3)")) << r.err;
    // A sequence plays the animation: its note says so once, at the first frame, with the
    // camera every frame uses, and never that the animation is not played.
    EXPECT_FALSE(contains(r.err, "not played")) << r.err;
    const size_t first = r.err.find("has no camera: framing it with");
    ASSERT_NE(first, std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("has no camera", first + 1), std::string::npos) << r.err;
    EXPECT_LT(first, r.err.find("glint: frame 2 (2 of 3)")) << r.err;
    EXPECT_TRUE(contains(r.err,
                         "posed by animation 0 'Slide' at 0.0416667 s, framed for the "
                         "whole animation"))
        << r.err;
}

TEST(CliAnimation, BadTimeOptionsSayWhatIsWrong) {
    std::string dir = animatedDir("anim-usage");
    struct Case {
        const char* args;
        int code;
        const char* message;
    } cases[] = {
        {"--frames 0:3 -o out.png", 2, "-o needs a frame number in its name, as out_%04d.png"},
        {"--frames 3:1", 2, "the last frame comes before the first in '3:1'"},
        {"--frames 1:3:0", 2, "the step must be at least 1"},
        {"--frames 1-3", 2, "expected A:B or A:B:STEP"},
        {"--frame 1 --time-at 2", 2, "excludes"},
        {"--frame 1 --frames 1:2", 2, "excludes"},
        {"--fps 0 --frame 1", 2, "--fps"},
        {"--animation Walk --frame 1", 1,
         "no animation is named 'Walk': the file has 1 "
         "animation: 0 = 'Slide' (0 to 2 s)"},
    };
    for (const Case& c : cases) {
        CommandResult r = runGlint(std::string("anim.gltf ") + c.args + kSmall, dir);
        EXPECT_EQ(r.exitCode, c.code) << c.args << "\n" << r.err;
        EXPECT_TRUE(contains(r.err, c.message)) << c.args << "\n" << r.err;
    }
}

TEST(CliAnimation, ASceneFilesMeshLinePlaysItsAnimation) {
    std::string dir = animatedDir("anim-scene");
    writeFile(dir + "/scene.test",
              "size 40 30\ncamera 0 0.5 4 0 0.5 0 0 1 0 40\n"
              "point 0 2 4 1 1 1\ndiffuse 0.8 0.8 0.8\nmesh anim.gltf\n");
    CommandResult r = runGlint("scene.test --frames 0:48:48 -o s_%02d.png -q", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(readBytes(dir + "/s_00.png"), readBytes(dir + "/s_48.png"));
    r = runGlint("scene.test --frame 48 -o alone.png -q", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(readBytes(dir + "/alone.png"), readBytes(dir + "/s_48.png"));
}

TEST(CliAnimation, AShutterBlursWhatMovesAndNothingElse) {
    std::string dir = animatedDir("anim-shutter");
    writeFile(dir + "/still.gltf", quad(R"("translation": [0, 0, 0])"));
    const std::string view = " --camera orbit:0,80,4,0,0.5,0 --ground none" + kSmall;
    ASSERT_EQ(runGlint("anim.gltf --frame 24 -o sharp.png" + view, dir).exitCode, 0);
    CommandResult r = runGlint("anim.gltf --frame 24 --shutter -6:6 -o blur.png" + view, dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(readBytes(dir + "/blur.png"), readBytes(dir + "/sharp.png"));
    // A shutter of zero length is the still frame; so is a still model with a shutter.
    ASSERT_EQ(runGlint("anim.gltf --frame 24 --shutter 0:0 -o zero.png" + view, dir).exitCode, 0);
    EXPECT_EQ(readBytes(dir + "/zero.png"), readBytes(dir + "/sharp.png"));
    ASSERT_EQ(runGlint("still.gltf -o s.png" + view, dir).exitCode, 0);
    ASSERT_EQ(runGlint("still.gltf --shutter -0.5:0.5 -o s2.png" + view, dir).exitCode, 0);
    EXPECT_EQ(readBytes(dir + "/s.png"), readBytes(dir + "/s2.png"));
    for (const char* bad :
         {"--shutter 1:0", "--shutter 0.5", "--shutter a:b", "--shutter 0:2000"}) {
        r = runGlint(std::string("anim.gltf ") + bad + kSmall, dir);
        EXPECT_EQ(r.exitCode, 2) << bad;
        EXPECT_TRUE(contains(r.err, "--shutter")) << bad << "\n" << r.err;
    }
}

TEST(CliAnimation, PiecesOfOneFrameMergeAndPiecesOfTwoDoNot) {
    std::string dir = animatedDir("anim-pieces");
    const std::string common = "anim.gltf --size 40x30 --spp 2 -q";
    ASSERT_EQ(runGlint(common + " --frame 5 --part 0/2 -o a.exr", dir).exitCode, 0);
    ASSERT_EQ(runGlint(common + " --frame 5 --part 1/2 -o b.exr", dir).exitCode, 0);
    ASSERT_EQ(runGlint(common + " --frame 6 --part 1/2 -o c.exr", dir).exitCode, 0);
    CommandResult r = runGlint("merge -o m.png a.exr b.exr", dir);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    r = runGlint("merge -o n.png a.exr c.exr", dir);
    EXPECT_NE(r.exitCode, 0);
    EXPECT_TRUE(contains(r.err, "time=")) << r.err;
    // Pieces of a sequence: one file per frame and piece.
    r = runGlint(common + " --frames 5:6 --part 0/2 -o p%d.exr", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(readBytes(dir + "/p5.exr"), readBytes(dir + "/a.exr"));
}

}  // namespace
}  // namespace glint::test
