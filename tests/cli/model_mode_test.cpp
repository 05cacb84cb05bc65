// The model mode's defaults (`glint model.obj`): a studio render (the path tracer, the studio
// environment, a ground shadow, PBR Neutral and sRGB, adaptive sampling and the denoiser) that each
// option turns off or changes; the classic look with --integrator whitted; scene files keep the
// course's output;
// --environment, --tonemap, --srgb/--no-srgb, --ground and --time as a user meets them.

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "cli/cli_support.h"
#include "glint/io/image/image_io.h"

namespace glint::test {
namespace {

namespace fs = std::filesystem;

const std::string kMeshes = std::string(GLINT_TEST_DATA_DIR) + "/meshes/";

/// A fresh directory with tests/data/meshes/flat.obj (a tetrahedron) in it.
std::string withTetrahedron(const std::string& name) {
    std::string dir = freshDir(name);
    fs::copy_file(kMeshes + "flat.obj", dir + "/flat.obj");
    return dir;
}

/// A Radiance HDR file of 4 x 16 texels: the upper half `top`, the lower `bottom`, each given
/// as the RGBE mantissa and exponent of a grey (value m 2^(e - 136)).
std::string hdrFile(int topMantissa, int topExponent, int bottomMantissa, int bottomExponent) {
    std::string s = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 16 +X 4\n";
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 4; ++x) {
            char m = static_cast<char>(y < 8 ? topMantissa : bottomMantissa);
            char e = static_cast<char>(y < 8 ? topExponent : bottomExponent);
            s += std::string{m, m, m, e};
        }
    return s;
}

/// A course scene: a red sphere under a point light, seen against the black background.
const char* kCourseScene =
    "size 32 24\ncamera 0 0 4 0 0 0 0 1 0 45\npoint 2 2 2 1 1 1\ndiffuse 0.9 0.2 0.2\n"
    "ambient 0.05 0.05 0.05\nsphere 0 0 0 1\n";

TEST(CliModelMode, IsAStudioRenderByDefault) {
    std::string dir = withTetrahedron("mode-default");
    CommandResult r = runGlint("flat.obj --size 24x18 -o default.png", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(contains(r.err, "showing it in the studio environment with a ground shadow"))
        << r.err;
    // Sampled until clean (or the time cap), then denoised (tests/cli/clean_images_test.cpp).
    EXPECT_TRUE(contains(r.err, "glint: adaptive sampling (a model's default)")) << r.err;
    EXPECT_TRUE(contains(r.err, "glint: denoised in ")) << r.err;
    // Every other default, spelled out, gives the same bytes: the path tracer, PBR Neutral,
    // sRGB, the studio environment and the ground shadow.
    r = runGlint("-q flat.obj --size 24x18 --spp 64 --no-denoise -o fixed.png", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    r = runGlint(
        "-q flat.obj --size 24x18 --integrator path --spp 64 --no-denoise --tonemap neutral "
        "--srgb --environment studio --ground shadow -o explicit.png",
        dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(readBytes(dir + "/fixed.png"), readBytes(dir + "/explicit.png"));
    // The ground in the corner is a light, neutral grey (as rendered: the network denoiser
    // tints an image's last few pixels slightly, as Open Image Denoise does, and this one is
    // tiny).
    Image8 img = readImage8(dir + "/fixed.png", 3);
    EXPECT_EQ(img.at(0, 17, 0), img.at(0, 17, 1));
    EXPECT_EQ(img.at(0, 17, 1), img.at(0, 17, 2));
    EXPECT_GT(img.at(0, 17, 0), 150);
    EXPECT_LT(img.at(0, 17, 0), 235);
}

TEST(CliModelMode, EachDefaultCanBeChanged) {
    std::string dir = withTetrahedron("mode-options");
    auto render = [&](const std::string& options, const std::string& out) {
        CommandResult r = runGlint("flat.obj --size 24x18 --spp 4 " + options + " -o " + out, dir);
        EXPECT_EQ(r.exitCode, 0) << options << ": " << r.err;
        return r;
    };
    render("", "default.png");
    const std::string base = readBytes(dir + "/default.png");
    struct Case {
        const char* options;
        const char* said;  ///< In the note.
    } cases[] = {
        {"--ground none", "showing it in the studio environment\n"},
        {"--ground floor", "showing it in the studio environment on a grey floor at y = "},
        {"--environment none",
         "showing it in the dark, lit by a key and a fill directional light, with a ground "
         "shadow"},
        {"--tonemap clamp", "with a ground shadow"},
        {"--tonemap aces", "with a ground shadow"},
        {"--no-srgb", "with a ground shadow"},
    };
    int n = 0;
    for (const Case& c : cases) {
        std::string out = "case" + std::to_string(n++) + ".png";
        CommandResult r = render(c.options, out);
        EXPECT_TRUE(contains(r.err, c.said)) << c.options << ": " << r.err;
        EXPECT_NE(readBytes(dir + "/" + out), base) << c.options << " changed nothing";
    }
    // A ground shadow needs the path tracer.
    CommandResult r = runGlint("flat.obj --integrator whitted --ground shadow", dir);
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_TRUE(contains(r.err, "glint: error: --ground shadow needs the path tracer")) << r.err;
    r = runGlint("flat.obj --ground sand", dir);
    EXPECT_EQ(r.exitCode, 2);
    r = runGlint("flat.obj --tonemap filmic", dir);
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_TRUE(contains(r.err, "--tonemap")) << r.err;
}

TEST(CliModelMode, WhittedGivesTheClassicLook) {
    // The course's integrator: a key and a fill light, a floor and a sky, the course's
    // conversion at one sample per pixel, as `glint model.obj` rendered before the studio.
    std::string dir = withTetrahedron("mode-classic");
    CommandResult r = runGlint("flat.obj --size 32x24 --integrator whitted -o classic.png", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(
        contains(r.err, "flat.obj has no camera or lights: framing it with a camera at (0.5, "))
        << r.err;
    EXPECT_TRUE(contains(r.err, "a key and a fill directional light, a grey floor at y = "))
        << r.err;
    r = runGlint(
        "-q flat.obj --size 32x24 --integrator whitted --spp 1 --tonemap clamp --no-srgb "
        "--ground floor -o explicit.png",
        dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(readBytes(dir + "/classic.png"), readBytes(dir + "/explicit.png"));
}

TEST(CliModelMode, SceneFilesKeepTheCoursesConversion) {
    std::string dir = freshDir("mode-course");
    writeFile(dir + "/s.test", kCourseScene);
    ASSERT_EQ(runGlint("-q s.test -o default.png", dir).exitCode, 0);
    ASSERT_EQ(runGlint("-q s.test --tonemap clamp --no-srgb -o explicit.png", dir).exitCode, 0);
    EXPECT_EQ(readBytes(dir + "/default.png"), readBytes(dir + "/explicit.png"));
    ASSERT_EQ(runGlint("-q s.test --tonemap neutral --srgb -o neutral.png", dir).exitCode, 0);
    EXPECT_NE(readBytes(dir + "/default.png"), readBytes(dir + "/neutral.png"));
    // --ground is for models: a warning, and the same image.
    CommandResult r = runGlint("s.test --ground floor -o ground.png", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(contains(r.err,
                         "glint: warning: --ground applies to models (.obj, .gltf, .glb) only; "
                         "'s.test' is a scene: ignored"))
        << r.err;
    EXPECT_EQ(readBytes(dir + "/default.png"), readBytes(dir + "/ground.png"));
    // The tone mapper and the curve are for 8-bit files: asked for with a float file, a warning.
    r = runGlint("s.test --tonemap neutral -o linear.pfm", dir);
    EXPECT_TRUE(contains(r.err,
                         "glint: warning: --tonemap applies to 8-bit outputs (.png, .ppm) "
                         "only; 'linear.pfm' is written linear"))
        << r.err;
    // A model's own defaults say nothing of the kind.
    fs::copy_file(kMeshes + "flat.obj", dir + "/flat.obj");
    r = runGlint("flat.obj --size 8x6 --spp 2 -o model.pfm", dir);
    EXPECT_FALSE(contains(r.err, "warning")) << r.err;
}

TEST(CliModelMode, EnvironmentTakesAFileStudioOrNone) {
    std::string dir = withTetrahedron("mode-environment");
    writeFile(dir + "/sky.hdr", hdrFile(128, 128, 128, 127));  // 0.5 above, 0.25 below
    // A scene that sees nothing but its surroundings: the map, in place of the background.
    writeFile(dir + "/empty.test", "size 4 4\ncamera 0 0 0 0 0 -1 0 1 0 30\n");
    CommandResult r = runGlint("-q empty.test --environment sky.hdr -o sky.pfm", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    Film f = readPfm(dir + "/sky.pfm");
    EXPECT_NEAR(f.at(1, 0).x, 0.5, 1e-6);   // above the horizon
    EXPECT_NEAR(f.at(1, 3).x, 0.25, 1e-6);  // below it
    ASSERT_EQ(runGlint("-q empty.test --environment studio -o studio.pfm", dir).exitCode, 0);
    EXPECT_GT(readPfm(dir + "/studio.pfm").at(1, 3).x, 0.3);  // the studio's light ground
    ASSERT_EQ(runGlint("-q empty.test -o none.pfm", dir).exitCode, 0);
    EXPECT_EQ(readPfm(dir + "/none.pfm").at(1, 3).x, 0);  // the course's black
    // A model in another map.
    r = runGlint("flat.obj --size 16x12 --spp 2 --environment sky.hdr", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(contains(r.err, "showing it in the environment map with a ground shadow")) << r.err;
    // A file that cannot be read: exit 1, before anything is rendered.
    r = runGlint("flat.obj --environment nowhere.hdr -o x.png", dir);
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_TRUE(contains(r.err,
                         "glint: error: --environment: cannot read environment map "
                         "'nowhere.hdr'"))
        << r.err;
    EXPECT_FALSE(fs::exists(dir + "/x.png"));
}

TEST(CliModelMode, TimeRendersPassesUntilTheBudgetIsSpent) {
    std::string dir = withTetrahedron("mode-time");
    CommandResult r = runGlint("flat.obj --size 16x12 --time 0.3", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(contains(r.err, " samples per pixel in ")) << r.err;
    // With --spp, the samples stop there if the time has not run out first.
    r = runGlint("flat.obj --size 16x12 --time 1000 --spp 12", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(contains(r.err, "glint: rendered 12 samples per pixel in ")) << r.err;
    for (const char* bad : {"0", "-1", "abc", "1e9"}) {
        r = runGlint(std::string("flat.obj --time ") + bad, dir);
        EXPECT_EQ(r.exitCode, 2) << bad;
        EXPECT_TRUE(contains(r.err, "--time")) << r.err;
    }
}

}  // namespace
}  // namespace glint::test
