// Scene diagnostics as the CLI prints them: `file:line:col: error: ...` (exit 1, no image) and
// `file:line:col: warning: ...` (the render still succeeds), plus the file syntax the loader
// accepts. The messages are part of the user interface: docs/scene-format.md lists them.

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "cli/cli_support.h"
#include "glint/io/image/image_io.h"

namespace glint::test {
namespace {

namespace fs = std::filesystem;

/// Two valid lines; a case's own lines start at line 3.
const std::string kHead = "size 64 48\ncamera 0 0 5 0 0 0 0 1 0 45\n";

struct ErrorCase {
    const char* name;
    std::string scene;     ///< Contents of e.test.
    std::string expected;  ///< The whole of stderr, one line.
};

void PrintTo(const ErrorCase& c, std::ostream* os) { *os << c.name; }

class SceneErrorMessage : public testing::TestWithParam<ErrorCase> {};

TEST_P(SceneErrorMessage, ExitsOneWithFileLineColumnMessageAndWritesNothing) {
    const ErrorCase& c = GetParam();
    std::string dir = freshDir(std::string("err-") + c.name);
    writeFile(dir + "/e.test", c.scene);
    CommandResult r = runGlint("e.test", dir);
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_EQ(r.err, c.expected + "\n");
    EXPECT_EQ(r.out, "");
    EXPECT_FALSE(fs::exists(dir + "/e.png"));
}

const ErrorCase kErrorCases[] = {
    {"UnknownCommandSuggestsTheNearestOne", kHead + "sphre 0 0 0 1\n",
     "e.test:3:1: error: unknown command 'sphre' (--lenient skips unknown commands); did you "
     "mean 'sphere'?"},
    {"UnknownCommandIsCaseSensitiveButSuggestsTheSpelling", kHead + "PushTransform\n",
     "e.test:3:1: error: unknown command 'PushTransform' (--lenient skips unknown commands); "
     "did you mean 'pushTransform'?"},
    {"UnknownCommandFarFromAnyHasNoSuggestion", kHead + "frobnicate 1 2\n",
     "e.test:3:1: error: unknown command 'frobnicate' (--lenient skips unknown commands)"},
    {"TooFewArgumentsPointsAtTheCommand", kHead + "  sphere 0 0 0\n",
     "e.test:3:3: error: sphere expects 4 arguments (x y z radius), got 3"},
    {"TooManyArgumentsPointsAtTheFirstExtra", kHead + "sphere 0 0 0 1 2\n",
     "e.test:3:16: error: sphere expects 4 arguments (x y z radius), got 5"},
    {"BackgroundTakesThreeOrSixArguments", kHead + "background 1 1 1 1\n",
     "e.test:3:18: error: background expects 3 or 6 arguments (r g b [r2 g2 b2]), got 4"},
    {"NonNumberArgument", kHead + "sphere 0 0 x 1\n",
     "e.test:3:12: error: expected a number, got 'x'"},
    {"NanIsRejected", kHead + "sphere 0 0 nan 1\n",
     "e.test:3:12: error: expected a finite number, got 'nan'"},
    {"InfinityIsRejected", kHead + "point 0 0 0 inf 1 1\n",
     "e.test:3:13: error: expected a finite number, got 'inf'"},
    {"NumberBeyondFloatRangeIsRejected", kHead + "translate 1e39 0 0\n",
     "e.test:3:11: error: number '1e39' is too large"},
    {"HashInsideATokenIsNotAComment", kHead + "sphere 0 0 0 1#c\n",
     "e.test:3:14: error: expected a number, got '1#c'"},
    {"TriIndexOutOfRangeNamesTheValidRange",
     kHead + "vertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\ntri 0 1 3\n",
     "e.test:6:9: error: vertex index '3' is out of range: 3 vertices are defined (0 to 2)"},
    {"TriBeforeAnyVertex", kHead + "tri 0 1 2\n",
     "e.test:3:5: error: vertex index '0' is out of range: no vertex has been defined yet"},
    {"TriIndexMustBeAnInteger", kHead + "vertex 0 0 0\ntri 0 0.5 0\n",
     "e.test:4:7: error: expected an integer, got '0.5'"},
    {"TriNormalUsesItsOwnPile", kHead + "vertex 0 0 0\ntrinormal 0 0 0\n",
     "e.test:4:11: error: vertex index '0' is out of range: no vertexnormal has been defined "
     "yet"},
    {"ZeroImageSize", "size 0 48\ncamera 0 0 5 0 0 0 0 1 0 45\n",
     "e.test:1:6: error: integer '0' is out of range (1 to 32768)"},
    {"ImageTooLarge", "size 30000 30000\ncamera 0 0 5 0 0 0 0 1 0 45\n",
     "e.test:1:12: error: image of 30000 x 30000 pixels is too large (at most 134217728 "
     "pixels)"},
    {"ZeroScale", kHead + "scale 1 0 1\n",
     "e.test:3:9: error: scale by zero would make the transform singular"},
    {"ZeroRotationAxis", kHead + "rotate 0 0 0 45\n",
     "e.test:3:8: error: rotation axis must not be zero"},
    {"CameraUpParallelToViewingDirection", "size 64 48\ncamera 0 0 5 0 0 0 0 0 1 45\n",
     "e.test:2:20: error: the camera's up vector is zero or parallel to the viewing direction"},
    {"CameraLooksAtItself", "camera 1 2 3 1 2 3 0 1 0 45\n",
     "e.test:1:14: error: the camera looks at its own position (from equals at)"},
    {"FovyOutOfRange", "camera 0 0 5 0 0 0 0 1 0 180\n",
     "e.test:1:26: error: fovy must be between 0 and 180 degrees, got '180'"},
    {"PopTransformOnEmptyStack", kHead + "pushTransform\npopTransform\npopTransform\n",
     "e.test:5:1: error: popTransform without a matching pushTransform (--lenient ignores it)"},
    {"NegativeSphereRadius", kHead + "sphere 0 0 0 -1\n",
     "e.test:3:14: error: sphere radius must not be negative, got '-1'"},
    {"ZeroDirectionalLight", kHead + "directional 0 0 0 1 1 1\n",
     "e.test:3:13: error: light direction must not be zero"},
    {"AllZeroAttenuation", kHead + "attenuation 0 0 0\n",
     "e.test:3:13: error: attenuation coefficients must not all be zero"},
    {"NegativeShininess", kHead + "shininess -2\n",
     "e.test:3:11: error: shininess must not be negative, got '-2'"},
    {"MissingCameraPointsAtTheFirstCommand", "# a ball\n  size 64 48\nsphere 0 0 0 1\n",
     "e.test:2:3: error: the scene has no camera (add 'camera fromx fromy fromz atx aty atz upx "
     "upy upz fovy')"},
    {"EmptyFileSaysSo", "# nothing yet\n\n", "e.test: error: the scene file has no commands"},
    {"CrlfLinesReportTheSameColumns",
     "size 64 48\r\ncamera 0 0 5 0 0 0 0 1 0 45\r\nsphere 0 0 x 1\r\n",
     "e.test:3:12: error: expected a number, got 'x'"},
    // The shape extensions.
    {"MisspelledShapeSuggestsIt", kHead + "cylindre 0 0 0 0 0 1 1\n",
     "e.test:3:1: error: unknown command 'cylindre' (--lenient skips unknown commands); did "
     "you mean 'cylinder'?"},
    {"BoxWithZeroExtent", kHead + "box 0 0 0 1 0 1\n",
     "e.test:3:13: error: box has zero extent along y: both corners have y = '0'"},
    {"ConeWithBothRadiiZero", kHead + "cone 0 0 0 0 0 0 1 0\n",
     "e.test:3:12: error: cone radii must not both be zero"},
    {"PlaneWithZeroNormal", kHead + "plane 0 0 0 0 0 0\n",
     "e.test:3:13: error: plane normal must not be zero"},
    {"PolygonWithCrossingEdges",
     kHead + "vertex 0 0 0\nvertex 2 2 0\nvertex 2 0 0\nvertex 0 1 0\npolygon 0 1 2 3\n",
     "e.test:7:13: error: the polygon's edges cross: the edge from vertex '2' to '3' meets the "
     "edge from vertex '0' to '1'"},
    // The environment map.
    {"EnvironmentFileMissing", kHead + "environment sky.hdr 2\n",
     "e.test:3:13: error: cannot read environment map 'sky.hdr': No such file or directory"},
    {"EnvironmentNotAnHdrImage", kHead + "environment e.test\n",
     "e.test:3:13: error: cannot read environment map 'e.test': not a Radiance HDR (.hdr) or "
     "OpenEXR (.exr) file"},
    {"EnvironmentNegativeScale", kHead + "environment sky.hdr -2\n",
     "e.test:3:21: error: environment scale must not be negative, got '-2'"},
};

INSTANTIATE_TEST_SUITE_P(Cli, SceneErrorMessage, testing::ValuesIn(kErrorCases),
                         [](const testing::TestParamInfo<ErrorCase>& p) {
                             return std::string(p.param.name);
                         });

TEST(CliSceneErrors, MessagesNameTheSceneAsGivenOnTheCommandLine) {
    std::string dir = freshDir("errpath");
    writeFile(dir + "/sub/dir/bad.test", kHead + "sphre 0 0 0 1\n");
    CommandResult r = runGlint("./sub/dir/bad.test", dir);
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_TRUE(contains(r.err, "./sub/dir/bad.test:3:1: error: unknown command")) << r.err;
}

TEST(CliSceneErrors, CheckReportsTheSameErrorAsRendering) {
    std::string dir = freshDir("errcheck");
    writeFile(dir + "/e.test", kHead + "pushTransform\nscale 2 0 2\n");
    CommandResult render = runGlint("e.test", dir);
    CommandResult check = runGlint("--check e.test", dir);
    EXPECT_EQ(check.exitCode, 1);
    EXPECT_EQ(check.err, "e.test:4:9: error: scale by zero would make the transform singular\n");
    EXPECT_EQ(check.err, render.err);
}

TEST(CliSceneWarnings, AreFileLineColumnLinesAndTheRenderStillSucceeds) {
    std::string dir = freshDir("warnings");
    writeFile(dir + "/w.test", kHead +
                                   "maxdepth 100\n"
                                   "sphere 0 0 0 0\n"
                                   "camera 0 0 6 0 0 0 0 1 0 45\n"
                                   "maxverts 1\nvertex 0 0 0\nvertex 1 0 0\n"
                                   "maxvertnorms 0\nvertexnormal 0 0 0 0 0 0\n"
                                   "sphere 0 0 0 1\n");
    CommandResult r = runGlint("-q w.test", dir);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(r.err,
              "w.test:3:10: warning: maxdepth 100 is more than Glint traces; using 64\n"
              "w.test:4:14: warning: sphere of radius 0 is invisible and is skipped\n"
              "w.test:5:1: warning: a second camera replaces the one on line 2\n"
              "w.test:8:1: warning: more vertices than 'maxverts 1' announced\n"
              "w.test:10:20: warning: vertex normal has zero length: it adds nothing to "
              "interpolated normals (where nothing remains, the face normal is used)\n"
              "w.test:10:1: warning: more vertices with normals than 'maxvertnorms 0' "
              "announced\n");
    Image8 img = readImage8(dir + "/w.png", 3);
    EXPECT_EQ(img.width, 64);
    EXPECT_EQ(img.height, 48);
}

TEST(CliSceneWarnings, ArePrintedBeforeALaterError) {
    std::string dir = freshDir("warnthenerror");
    writeFile(dir + "/w.test", kHead + "maxdepth 70\nsphere 0 0 0\n");
    CommandResult r = runGlint("w.test", dir);
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_EQ(r.err,
              "w.test:3:10: warning: maxdepth 70 is more than Glint traces; using 64\n"
              "w.test:4:1: error: sphere expects 4 arguments (x y z radius), got 3\n");
}

TEST(CliSceneSyntax, AcceptsCommentsBlankLinesCrlfTabsAndNumberForms) {
    std::string dir = freshDir("syntax");
    writeFile(dir + "/s.test",
              "# a comment line\r\n"
              "\r\n"
              "   # an indented comment\n"
              "size +64 48   # a comment after the arguments\r\n"
              "\tcamera 0 0 5  0 0 0  0 1 0  45 \t \r\n"
              "\n"
              "sphere +1 .5 -.5 1.\n"
              "sphere 1e-1 +.5 -0.0 1E0\n"
              "maxdepth +2\n");
    CommandResult r = runGlint("--check s.test", dir);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(r.out,
              "s.test: ok: 64x48, 0 triangles, 2 spheres, 0 lights, maxdepth 2, output s.png\n");
    EXPECT_EQ(r.err, "");
}

TEST(CliSceneSyntax, DefaultsApplyWhenSizeAndMaxDepthAreAbsent) {
    std::string dir = freshDir("defaults");
    writeFile(dir + "/d.test", "camera 0 0 5 0 0 0 0 1 0 45\n");
    CommandResult r = runGlint("--check d.test", dir);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(contains(r.out, ": ok: 640x480,")) << r.out;
    EXPECT_TRUE(contains(r.out, "maxdepth 5,")) << r.out;
}

TEST(CliSceneSyntax, BackgroundGradientRunsFromDownColourToUpColour) {
    // The lecture's sky. A 1x1 image looks straight along -z (direction y = 0), halfway
    // between white and blue: (0.65, 0.75, 0.95) -> floor(255 c) = (165, 191, 242).
    std::string dir = freshDir("background");
    writeFile(dir + "/sky.test", "camera 0 0 5 0 0 0 0 1 0 45\nbackground 1 1 1 0.3 0.5 0.9\n");
    CommandResult r = runGlint("-q sky.test --size 1x1", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    Image8 img = readImage8(dir + "/sky.png", 3);
    ASSERT_EQ(img.width, 1);
    EXPECT_EQ(img.at(0, 0, 0), 165);
    EXPECT_EQ(img.at(0, 0, 1), 191);
    EXPECT_EQ(img.at(0, 0, 2), 242);

    // Without background the sky is black, as in the course.
    writeFile(dir + "/black.test", "camera 0 0 5 0 0 0 0 1 0 45\n");
    r = runGlint("-q black.test --size 1x1", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    img = readImage8(dir + "/black.png", 3);
    EXPECT_EQ(img.at(0, 0, 0) + img.at(0, 0, 1) + img.at(0, 0, 2), 0);
}

}  // namespace
}  // namespace glint::test
