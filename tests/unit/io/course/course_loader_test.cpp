#include "glint/io/course/course_loader.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <optional>

#include "unit/io/course/course_test_support.h"
#include "unit/test_support.h"

namespace glint {
namespace {

using namespace test;  // NOLINT: the loader test helpers

using ::testing::HasSubstr;
using ::testing::Not;
namespace fs = std::filesystem;

void expectBounds(const Bounds3f& b, const Vec3& lo, const Vec3& hi, double eps = 1e-5) {
    expectNear(Vec3(b.lo), lo, eps);
    expectNear(Vec3(b.hi), hi, eps);
}

/// The material of whatever the ray straight down the -z axis through (x, y) hits first.
Material materialAt(Scene& scene, double x, double y) {
    auto si = shoot(scene, {x, y, 50}, {0, 0, -1});
    EXPECT_TRUE(si) << "nothing at " << x << ", " << y;
    return si ? scene.materials.at(si->material) : Material{};
}

// ---- general settings -------------------------------------------------------------------

TEST(CourseLoader, ReadsSizeMaxDepthAndOutput) {
    auto s = parseOk("size 320 200\nmaxdepth 3\noutput picture.png\n");
    EXPECT_EQ(s->width, 320);
    EXPECT_EQ(s->height, 200);
    EXPECT_EQ(s->maxDepth, 3);
    EXPECT_EQ(s->output, "picture.png");
    EXPECT_EQ(parseOk("maxdepth 0\n")->maxDepth, 0);
    EXPECT_EQ(parseOk("maxdepth 64\n")->maxDepth, 64);
}

TEST(CourseLoader, DefaultsAreMaxDepthFiveNoOutputBlackBackgroundNoLights) {
    auto s = parseOk("");
    EXPECT_EQ(s->maxDepth, 5);
    EXPECT_EQ(s->output, "");
    EXPECT_EQ(s->background.down, Vec3(0));
    EXPECT_EQ(s->background.up, Vec3(0));
    EXPECT_TRUE(s->lights.empty());
    EXPECT_EQ(s->primitives.size(), 0u);
}

TEST(CourseLoader, MaxDepthAboveSixtyFourIsClampedWithAWarning) {
    std::unique_ptr<Scene> s;
    Diagnostic w = warningOf("maxdepth 65\n", &s);
    EXPECT_EQ(s->maxDepth, 64);
    EXPECT_EQ(w.loc.line, 1);
    EXPECT_EQ(w.loc.column, 10);
    EXPECT_THAT(w.message, HasSubstr("64"));
}

TEST(CourseLoader, CameraIsStoredAsGivenWithAnyNonParallelUp) {
    std::vector<Diagnostic> w;
    auto s = parse("camera 1 2 3 4 5 6 0 1 0 30\n", w);
    ASSERT_TRUE(s->camera);
    EXPECT_EQ(s->camera->eye, Vec3(1, 2, 3));
    EXPECT_EQ(s->camera->center, Vec3(4, 5, 6));
    EXPECT_EQ(s->camera->up, Vec3(0, 1, 0));
    EXPECT_EQ(s->camera->fovyDegrees, 30);
    // The up vector need not be orthogonal to the viewing direction.
    EXPECT_EQ(parse("camera 0 0 5 0 0 0 0 1 1 45\n", w)->camera->up, Vec3(0, 1, 1));
    EXPECT_TRUE(w.empty());
}

TEST(CourseLoader, BackgroundTakesOneColourOrAGradientFromDownToUp) {
    auto flat = parseOk("background 0.1 0.2 0.3\n");
    EXPECT_EQ(flat->background.down, Vec3(0.1, 0.2, 0.3));
    EXPECT_EQ(flat->background.up, Vec3(0.1, 0.2, 0.3));
    auto grad = parseOk("background 0.1 0.2 0.3 0.4 0.5 0.6\n");
    EXPECT_EQ(grad->background.down, Vec3(0.1, 0.2, 0.3));
    EXPECT_EQ(grad->background.up, Vec3(0.4, 0.5, 0.6));
}

TEST(CourseLoader, CommandNamesListEveryCommand) {
    auto names = courseCommandNames();
    for (const char* c :
         {"size",         "maxdepth",     "output",    "camera",       "sphere",
          "maxverts",     "maxvertnorms", "vertex",    "vertexnormal", "tri",
          "trinormal",    "translate",    "rotate",    "scale",        "pushTransform",
          "popTransform", "directional",  "point",     "attenuation",  "ambient",
          "diffuse",      "specular",     "shininess", "emission",     "background"})
        EXPECT_NE(std::find(names.begin(), names.end(), c), names.end()) << c;
}

// ---- geometry and transforms ------------------------------------------------------------

TEST(CourseLoader, SphereHasItsCentreAndRadius) {
    auto s = parseOk("sphere 1 2 3 0.5\n");
    ASSERT_EQ(s->primitives.sphereCount(), 1u);
    expectBounds(s->primitives.bounds(0), {0.5, 1.5, 2.5}, {1.5, 2.5, 3.5});
}

TEST(CourseLoader, NonUniformScaleMakesAnEllipsoid) {
    auto s = parseOk("scale 2 1 0.5\nsphere 0 0 0 1\n");
    expectBounds(s->primitives.bounds(0), {-2, -1, -0.5}, {2, 1, 0.5});
    // The top of the ellipsoid is at z = 0.5 and faces +z.
    auto si = shoot(*s, {0, 0, 10}, {0, 0, -1});
    ASSERT_TRUE(si);
    expectNear(si->p, {0, 0, 0.5}, 1e-6);
    expectNear(si->n, {0, 0, 1}, 1e-6);
    // Rotated after the scale, the long axis lies along y.
    auto r = parseOk("rotate 0 0 1 90\nscale 3 1 1\nsphere 0 0 0 1\n");
    expectBounds(r->primitives.bounds(0), {-1, -3, -1}, {1, 3, 1});
}

TEST(CourseLoader, TransformsRightMultiplySoTheLastCommandActsFirst) {
    // Scaled first (centre 1 -> 2, radius 2), then translated by 1.
    auto s = parseOk("translate 1 0 0\nscale 2 2 2\nsphere 1 0 0 1\n");
    expectBounds(s->primitives.bounds(0), {1, -2, -2}, {5, 2, 2});
    // Translated first, then scaled: centre (1 + 1) * 2 = 4.
    auto t = parseOk("scale 2 2 2\ntranslate 1 0 0\nsphere 1 0 0 1\n");
    expectBounds(t->primitives.bounds(0), {2, -2, -2}, {6, 2, 2});
}

TEST(CourseLoader, RotateIsInDegreesCounterClockwiseAboutTheAxis) {
    auto z = parseOk("rotate 0 0 1 90\nsphere 2 0 0 0.5\n");  // x axis -> y axis
    expectBounds(z->primitives.bounds(0), {-0.5, 1.5, -0.5}, {0.5, 2.5, 0.5});
    auto x = parseOk("rotate 1 0 0 90\nsphere 0 2 0 0.5\n");  // y axis -> z axis
    expectBounds(x->primitives.bounds(0), {-0.5, -0.5, 1.5}, {0.5, 0.5, 2.5});
    auto unnormalised = parseOk("rotate 0 0 3 180\nsphere 2 0 0 0.5\n");
    expectBounds(unnormalised->primitives.bounds(0), {-2.5, -0.5, -0.5}, {-1.5, 0.5, 0.5});
}

TEST(CourseLoader, PopTransformRestoresThePushedMatrix) {
    auto s = parseOk(
        "translate 1 0 0\npushTransform\ntranslate 10 0 0\npushTransform\ntranslate 100 0 0\n"
        "sphere 0 0 0 1\npopTransform\nsphere 0 0 0 1\npopTransform\nsphere 0 0 0 1\n");
    ASSERT_EQ(s->primitives.sphereCount(), 3u);
    EXPECT_NEAR(s->primitives.bounds(0).lo.x, 110, 1e-4);
    EXPECT_NEAR(s->primitives.bounds(1).lo.x, 10, 1e-4);
    EXPECT_NEAR(s->primitives.bounds(2).lo.x, 0, 1e-5);
}

TEST(CourseLoader, TriangleUsesTheVertexPileWithZeroBasedIndices) {
    auto s =
        parseOk("maxverts 4\nvertex 9 9 9\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 2 0\ntri 1 2 3\n");
    ASSERT_EQ(s->primitives.triangleCount(), 1u);
    expectBounds(s->primitives.bounds(0), {0, 0, 0}, {1, 2, 0});
}

TEST(CourseLoader, TriangleFaceNormalFollowsTheVertexOrderAndIsNotFlipped) {
    auto ccw = parseOk(kVerts + "tri 0 1 2\n");
    auto si = shoot(*ccw, {0.25, 0.25, 5}, {0, 0, -1});
    ASSERT_TRUE(si);
    expectNear(si->p, {0.25, 0.25, 0}, 1e-6);
    expectNear(si->ng, {0, 0, 1});
    expectNear(si->n, {0, 0, 1});
    auto cw = parseOk(kVerts + "tri 0 2 1\n");
    si = shoot(*cw, {0.25, 0.25, 5}, {0, 0, -1});
    ASSERT_TRUE(si);
    expectNear(si->ng, {0, 0, -1});
}

TEST(CourseLoader, TriangleTakesTheTransformInEffectWhenIssuedNotWhenVerticesWereDefined) {
    auto s = parseOk(
        "pushTransform\nscale 10 10 10\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\npopTransform\n"
        "tri 0 1 2\ntranslate 0 0 -2\ntri 0 1 2\n");
    ASSERT_EQ(s->primitives.triangleCount(), 2u);
    expectBounds(s->primitives.bounds(0), {0, 0, 0}, {1, 1, 0});
    expectBounds(s->primitives.bounds(1), {0, 0, -2}, {1, 1, -2});
}

TEST(CourseLoader, TriNormalInterpolatesNormalisedVertexNormals) {
    // At (1, 0.5) the barycentrics are 0.25 (A), 0.5 (B), 0.25 (C). B's normal (3, 0, 0) is
    // normalised to (1, 0, 0) first, so the blend is (0.5, 0, 0.5), normalised.
    auto s = parseOk(
        "maxvertnorms 3\nvertexnormal 0 0 0 0 0 1\nvertexnormal 2 0 0 3 0 0\n"
        "vertexnormal 0 2 0 0 0 1\ntrinormal 0 1 2\n");
    ASSERT_EQ(s->primitives.triangleCount(), 1u);
    auto si = shoot(*s, {1, 0.5, 5}, {0, 0, -1});
    ASSERT_TRUE(si);
    expectNear(si->p, {1, 0.5, 0}, 1e-6);
    expectNear(si->ng, {0, 0, 1});
    expectNear(si->n, {std::sqrt(0.5), 0, std::sqrt(0.5)}, 1e-6);
}

TEST(CourseLoader, TriNormalNormalsUseTheInverseTransposeOfTheTransform) {
    // Scale x by 2: the normal (1, 0, 1) becomes (0.5, 0, 1), not (2, 0, 1).
    auto s = parseOk(
        "vertexnormal 0 0 0 1 0 1\nvertexnormal 1 0 0 1 0 1\nvertexnormal 0 1 0 1 0 1\n"
        "scale 2 1 1\ntrinormal 0 1 2\n");
    expectBounds(s->primitives.bounds(0), {0, 0, 0}, {2, 1, 0});
    auto si = shoot(*s, {0.5, 0.25, 5}, {0, 0, -1});
    ASSERT_TRUE(si);
    expectNear(si->n, normalize(Vec3(0.5, 0, 1)), 1e-6);
}

TEST(CourseLoader, VertexAndVertexNormalPilesAreSeparate) {
    // Three vertexnormal entries do not make 'tri 0 1 2' valid, and vice versa.
    expectError(kNormalVerts + "tri 0 1 2\n", 4, 5, "vertex");
    expectError(kVerts + "trinormal 0 1 2\n", 4, 11, "vertexnormal");
}

TEST(CourseLoader, HugeMaxVertsIsOnlyAHint) {
    auto s = parseOk("maxverts 999999999999\nmaxvertnorms 999999999999\n" + kVerts + "tri 0 1 2\n");
    EXPECT_EQ(s->primitives.triangleCount(), 1u);
}

// ---- materials --------------------------------------------------------------------------

TEST(CourseLoader, MaterialStateAppliesToEachPrimitiveAsItIsCreated) {
    auto s = parseOk(
        "diffuse 1 0 0\nspecular 0 1 0\nshininess 7\nemission 0 0 1\nsphere -3 0 0 1\n"
        "ambient 0 1 0\ndiffuse 0 0 1\nsphere 3 0 0 1\n");
    Material a = materialAt(*s, -3, 0);
    EXPECT_EQ(a.ambient, Vec3(0.2));  // the course default
    EXPECT_EQ(a.diffuse, Vec3(1, 0, 0));
    EXPECT_EQ(a.specular, Vec3(0, 1, 0));
    EXPECT_EQ(a.shininess, 7);
    EXPECT_EQ(a.emission, Vec3(0, 0, 1));
    Material b = materialAt(*s, 3, 0);
    EXPECT_EQ(b.ambient, Vec3(0, 1, 0));
    EXPECT_EQ(b.diffuse, Vec3(0, 0, 1));
    EXPECT_EQ(b.specular, Vec3(0, 1, 0));  // unchanged state carries over
    EXPECT_EQ(b.shininess, 7);
}

TEST(CourseLoader, UnsetMaterialIsAmbientPointTwoAndOtherwiseBlack) {
    auto s = parseOk("vertex -1 -1 0\nvertex 1 -1 0\nvertex 0 1 0\ntri 0 1 2\n");
    Material m = materialAt(*s, 0, 0);
    EXPECT_EQ(m.ambient, Vec3(0.2));
    EXPECT_EQ(m.diffuse, Vec3(0));
    EXPECT_EQ(m.specular, Vec3(0));
    EXPECT_EQ(m.emission, Vec3(0));
}

TEST(CourseLoader, PushAndPopDoNotSaveOrRestoreMaterials) {
    auto s = parseOk(
        "diffuse 1 0 0\npushTransform\ndiffuse 0 1 0\nambient 0 0 1\npopTransform\n"
        "sphere 0 0 0 1\n");
    Material m = materialAt(*s, 0, 0);
    EXPECT_EQ(m.diffuse, Vec3(0, 1, 0));
    EXPECT_EQ(m.ambient, Vec3(0, 0, 1));
}

// ---- lights -----------------------------------------------------------------------------

TEST(CourseLoader, DirectionalLightPointsTowardsTheLightTransformedAsAVectorAndNormalised) {
    auto s = parseOk("directional 0 0 2 1 0.5 0.25\n");
    ASSERT_EQ(s->lights.size(), 1u);
    EXPECT_EQ(s->lights[0].kind, LightSpec::Kind::Directional);
    expectNear(s->lights[0].direction, {0, 0, 1});
    EXPECT_EQ(s->lights[0].color, Vec3(1, 0.5, 0.25));
    // Transformed as a vector.
    s = parseOk(
        "translate 5 5 5\nrotate 0 0 1 90\n"
        "directional 1 0 0 1 1 1\n"  // rotated to +y; the translation does not apply
        "scale 2 1 1\n"
        "directional 1 -1 0 1 1 1\n");  // scale: (1, -1) -> (2, -1) -> rotate -> (1, 2)
    ASSERT_EQ(s->lights.size(), 2u);
    expectNear(s->lights[0].direction, {0, 1, 0});
    expectNear(s->lights[1].direction, normalize(Vec3(1, 2, 0)));
}

TEST(CourseLoader, PointLightPositionIsTransformed) {
    auto s = parseOk("translate 1 2 3\nrotate 0 0 1 90\npoint 1 0 0 0.1 0.2 0.3\n");
    ASSERT_EQ(s->lights.size(), 1u);
    EXPECT_EQ(s->lights[0].kind, LightSpec::Kind::Point);
    expectNear(s->lights[0].position, {1, 3, 3});
    EXPECT_EQ(s->lights[0].color, Vec3(0.1, 0.2, 0.3));
}

TEST(CourseLoader, SpotLightIsTransformedWithItsConeInDegreesAndTheCurrentAttenuation) {
    auto s = parseOk(
        "attenuation 0 0 1\ntranslate 1 2 3\nrotate 0 0 1 90\n"
        "spot 1 0 0  2 0 0  0.1 0.2 0.3  15 40\n");  // the axis +x, rotated to +y
    ASSERT_EQ(s->lights.size(), 1u);
    const LightSpec& l = s->lights[0];
    EXPECT_EQ(l.kind, LightSpec::Kind::Spot);
    expectNear(l.position, {1, 3, 3});
    expectNear(l.axis, {0, 1, 0});
    EXPECT_EQ(l.color, Vec3(0.1, 0.2, 0.3));
    EXPECT_NEAR(l.cosInner, std::cos(15 * std::numbers::pi / 180), 1e-12);
    EXPECT_NEAR(l.cosOuter, std::cos(40 * std::numbers::pi / 180), 1e-12);
    EXPECT_EQ(l.attenuation, Vec3(0, 0, 1));
    expectError("spot 0 0 0  0 0 0  1 1 1  10 20\n", 1, 13, "direction");
    expectError("spot 0 0 0  0 -1 0  1 1 1  -5 20\n", 1, 28, "inner cone angle");
    expectError("spot 0 0 0  0 -1 0  1 1 1  30 20\n", 1, 31, "outer cone angle");
    expectError("spot 0 0 0  0 -1 0  1 1 1  30 95\n", 1, 31, "outer cone angle");
}

TEST(CourseLoader, AttenuationDefaultsToNoneAndIsCapturedWhenALightIsDeclared) {
    std::unique_ptr<Scene> s;
    // Given after a point light, attenuation is a warning (course_leniency_test.cpp).
    warningOf("point 0 0 0 1 1 1\nattenuation 1 0.1 0.05\npoint 0 0 0 1 1 1\nattenuation 0 0 1\n",
              &s);
    ASSERT_EQ(s->lights.size(), 2u);
    EXPECT_EQ(s->lights[0].attenuation, Vec3(1, 0, 0));
    EXPECT_EQ(s->lights[1].attenuation, Vec3(1, 0.1, 0.05));
}

// ---- lexing -----------------------------------------------------------------------------

TEST(CourseLoader, LexerSkipsCommentsBlankLinesTabsAndTrailingSpaces) {
    auto s = parseOk(
        "# a comment\n\n   \t  \n   # an indented comment\n\tsize\t+320  240   \n"
        "sphere +1 .5 -.5 +.25 # centre and radius\n");
    EXPECT_EQ(s->width, 320);
    EXPECT_EQ(s->height, 240);
    ASSERT_EQ(s->primitives.sphereCount(), 1u);
    expectBounds(s->primitives.bounds(0), {0.75, 0.25, -0.75}, {1.25, 0.75, -0.25});
}

TEST(CourseLoader, CrlfLineEndingsAreAcceptedAndEveryLineCounts) {
    std::vector<Diagnostic> w;
    auto s = parse("size 4 3\r\n# comment\r\n\r\noutput a.png\r\n" + std::string("camera 0 0 5 ") +
                       "0 0 0 0 1 0 45\r\n",
                   w);
    EXPECT_TRUE(w.empty());
    EXPECT_EQ(s->width, 4);
    EXPECT_EQ(s->height, 3);
    EXPECT_EQ(s->output, "a.png");  // no trailing carriage return
    expectError("size 4 3\r\n# comment\r\n\r\nsphere 0 0 0 -1\r\n", 4, 14, "radius");
    // Comments and blank lines count; so does a last line without a newline.
    expectError("# one\n\n   # three\nsize 4 3\nsphere 0 0 0 -1", 5, 14, "radius");
}

// ---- errors -----------------------------------------------------------------------------

TEST(CourseLoader, UnknownCommandIsAnErrorSuggestingOnlyNearMisses) {
    Diagnostic d = errorOf("size 4 3\nsphre 0 0 0 1\n");
    EXPECT_EQ(d.loc.line, 2);
    EXPECT_EQ(d.loc.column, 1);
    EXPECT_THAT(d.message, HasSubstr("unknown command 'sphre'"));
    EXPECT_THAT(d.message, HasSubstr("did you mean 'sphere'"));
    // Commands are case-sensitive, but the suggestion ignores case.
    expectError("pushtransform\n", 1, 1, "did you mean 'pushTransform'");
    expectError("  Vertex 1 2 3\n", 1, 3, "did you mean 'vertex'");
    // Nothing is suggested for a word far from every command.
    d = errorOf("   frobnicate 1 2\n");
    EXPECT_EQ(d.loc.column, 4);
    EXPECT_THAT(d.message, HasSubstr("frobnicate"));
    EXPECT_THAT(d.message, Not(HasSubstr("did you mean")));
}

TEST(CourseLoader, TooFewArgumentsPointAtTheCommand) {
    Diagnostic d = errorOf("size 4 3\n  sphere 0 0 0\n");
    EXPECT_EQ(d.loc.line, 2);
    EXPECT_EQ(d.loc.column, 3);
    EXPECT_THAT(d.message, HasSubstr("sphere expects 4"));
    EXPECT_THAT(d.message, HasSubstr("got 3"));
    expectError("camera 0 0 5 0 0 0 0 1 0\n", 1, 1, "got 9");
}

TEST(CourseLoader, TooManyArgumentsPointAtTheFirstExtraOne) {
    expectError("sphere 0 0 0 1 2\n", 1, 16, "got 5");
    expectError("pushTransform 1\n", 1, 15, "got 1");
    expectError("camera 0 0 5 0 0 0 0 1 0 45 9\n", 1, 29, "got 11");
    // Far more tokens than any command takes.
    expectError("vertex 1 2 3 4 5 6 7 8 9 10 11 12 13 14\n", 1, 14, "got 14");
    expectError("background 1 2 3 4 5 6 7\n", 1, 24, "got 7");
    // background takes 3 or 6: 4 and 5 are errors too.
    Diagnostic d = errorOf("background 1 2 3 4\n");
    EXPECT_EQ(d.loc.line, 1);
    EXPECT_THAT(d.message, HasSubstr("3 or 6"));
    EXPECT_EQ(errorOf("background 1 2 3 4 5\n").loc.line, 1);
}

TEST(CourseLoader, NonNumbersAreErrorsAtTheirColumn) {
    expectError("sphere 0 0 zero 1\n", 1, 12, "expected a number, got 'zero'");
    expectError("translate 1 +-1 0\n", 1, 13, "expected a number");
    expectError("translate 1 2 +\n", 1, 15, "expected a number");
    expectError("vertex 1 2 3x\n", 1, 12, "expected a number");
}

TEST(CourseLoader, NanInfinityAndOverflowAreRejected) {
    expectError("sphere 0 0 0 nan\n", 1, 14, "nan");
    expectError("translate inf 0 0\n", 1, 11, "inf");
    expectError("sphere 1e999 0 0 1\n", 1, 8, "out of range");
    expectError("vertex 0 1e39 0\n", 1, 10, "too large");  // above the largest float
    expectError("diffuse 0 0 -1e39\n", 1, 13, "too large");
}

TEST(CourseLoader, IntegersAreRequiredForCountsAndIndices) {
    expectError("size 640.5 480\n", 1, 6, "integer");
    expectError("maxdepth 2.0\n", 1, 10, "integer");
    expectError("maxverts -1\n", 1, 10, "out of range");
    expectError("maxdepth -1\n", 1, 10, "out of range");
}

TEST(CourseLoader, ImageSizeMustBePositiveAndBounded) {
    expectError("size 0 480\n", 1, 6, "out of range");
    expectError("size 640 -480\n", 1, 10, "out of range");
    expectError("size 100000 100000\n", 1, 6, "out of range");
    Diagnostic d = errorOf("size 20000 20000\n");  // each side fine, the product is not
    EXPECT_EQ(d.loc.line, 1);
    EXPECT_THAT(d.message, HasSubstr("too large"));
}

TEST(CourseLoader, TriangleIndexOutOfRangeNamesTheBadIndex) {
    expectError(kVerts + "tri 0 1 3\n", 4, 9, "out of range");
    expectError(kVerts + "tri 0 -1 2\n", 4, 7, "out of range");
    expectError("tri 0 0 0\n", 1, 5, "no vertex");
    expectError("vertex 0 0 0\ntri 0 0 99999999999999999999\n", 2, 9, "out of range");
}

TEST(CourseLoader, TriNormalIndexOutOfRangeNamesTheBadIndex) {
    expectError(kNormalVerts + "trinormal 0 1 5\n", 4, 15, "out of range");
    expectError("trinormal 0 1 2\n", 1, 11, "no vertexnormal");
}

TEST(CourseLoader, DegenerateTransformsAreRejectedWhereGiven) {
    expectError("scale 1 0 1\n", 1, 9, "zero");
    expectError("scale 1 1 -0\n", 1, 11, "zero");
    expectError("rotate 0 0 0 45\n", 1, 8, "axis");
}

TEST(CourseLoader, TransformThatUnderflowsToSingularIsReportedAtThePrimitive) {
    expectError("scale 1e-200 1 1\nscale 1e-200 1 1\nsphere 0 0 0 1\n", 3, 1, "singular");
}

TEST(CourseLoader, GeometryThatATransformPushesBeyondFloatRangeIsAnError) {
    // Each number is below the float limit, but the transformed geometry (a vertex at 4e38, a
    // radius of 1e60) would be infinite in the float storage the numbers are checked against.
    EXPECT_EQ(
        errorOf("translate 3e38 0 0\n" + kVerts + "scale 1e38 1 1\ntri 0 1 2\n" + kCamera).loc.line,
        6);
    EXPECT_EQ(errorOf("scale 1e30 1e30 1e30\nsphere 0 0 0 1e30\n" + kCamera).loc.line, 2);
}

TEST(CourseLoader, GeometryBeyondTheCoordinateLimitIsAnErrorAtTheCommand) {
    // 1e18 is the documented limit for world coordinates (float search stays finite).
    expectError("translate 2e18 0 0\n" + kVerts + "tri 0 1 2\n" + kCamera, 5, 5,
                "supported coordinate range");
    EXPECT_EQ(errorOf("sphere 0 0 0 2e18\n" + kCamera).loc.line, 1);
    expectError("scale 1e-10 1e-10 1e-10\nsphere 0 0 0 1e-10\n" + kCamera, 2, 1, "too thin");
    // Just inside the limit is fine, for a triangle large enough to exist at that distance (a
    // unit triangle there collapses: the spacing of doubles near 9e17 is 128).
    auto scene = parseOk("translate 9e17 0 0\nscale 1e16 1e16 1e16\n" + kVerts + "tri 0 1 2\n");
    EXPECT_EQ(scene->primitives.triangleCount(), 1u);
}

TEST(CourseLoader, TinyRotationAxesAreNormalisedWithoutUnderflow) {
    // (1e-200, 0, 0) is a valid axis: squaring it would underflow to a zero length.
    auto scene = parseOk("rotate 0 0 1e-200 90\nsphere 2 0 0 0.5\n");
    // The sphere at x = 2 turns to y = 2.
    expectBounds(scene->primitives.bounds(0), {-0.5, 1.5, -0.5}, {0.5, 2.5, 0.5});
}

TEST(CourseLoader, NumbersThatUnderflowReadAsZero) {
    auto scene = parseOk("sphere 1e-400 0 0 1\n");
    expectBounds(scene->primitives.bounds(0), {-1, -1, -1}, {1, 1, 1});
    expectError("sphere 1e400 0 0 1\n" + kCamera, 1, 8, "out of range");
}

TEST(CourseLoader, HugeMaxDepthIsClampedLikeAnyOtherAboveTheLimit) {
    std::unique_ptr<Scene> scene;
    Diagnostic w = warningOf("maxdepth 99999999999\n", &scene);
    EXPECT_EQ(scene->maxDepth, kMaxDepthLimit);
    EXPECT_EQ(w.loc.line, 1);
    EXPECT_THAT(w.message, HasSubstr("using 64"));
}

TEST(CourseLoader, BackgroundWithFourOrFiveNumbersPointsAtTheFourth) {
    expectError("background 1 1 1 1\n" + kCamera, 1, 18, "3 or 6 arguments");
    expectError("background 1 1 1 1 1\n" + kCamera, 1, 18, "3 or 6 arguments");
}

TEST(CourseLoader, MaxVertsGivenAfterTheCountIsPassedStillWarns) {
    Diagnostic w = warningOf(kVerts + "maxverts 1\nvertex 2 2 2\n");
    EXPECT_EQ(w.loc.line, 5);
    EXPECT_THAT(w.message, HasSubstr("maxverts 1"));
}

TEST(CourseLoader, DegenerateTrianglesAreSkippedWithOneWarning) {
    std::vector<Diagnostic> warnings;
    auto scene = parse(
        "vertex 0 0 0\nvertex 1 1 1\nvertex 2 2 2\nvertex 0 1 0\n"
        "tri 0 1 2\ntri 0 0 3\ntri 0 1 3\n" +
            kCamera,
        warnings);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_EQ(warnings[0].loc.line, 5);
    EXPECT_THAT(warnings[0].message, HasSubstr("zero area"));
    EXPECT_EQ(scene->primitives.triangleCount(), 1u);
}

TEST(CourseLoader, ScenesNeedingMoreMemoryThanAvailableAreRefusedBeforeAllocating) {
    // 20,000 spheres need several megabytes; allow one.
    std::string text = kCamera;
    for (int i = 0; i < 20000; ++i) text += "sphere 0 0 0 1\n";
    std::vector<Diagnostic> warnings;
    try {
        parseCourseScene(text, "t.test", warnings, CourseOptions{LoadLimits{1 << 20}});
        ADD_FAILURE() << "no SceneError";
    } catch (const SceneError& e) {
        EXPECT_EQ(e.diagnostic().loc.line, 0);
        EXPECT_THAT(e.diagnostic().message, HasSubstr("needs about"));
        EXPECT_THAT(e.diagnostic().message, HasSubstr("20000 spheres"));
        EXPECT_THAT(e.diagnostic().message, HasSubstr("1 MiB available"));
    }
    // With room enough it loads.
    auto scene =
        parseCourseScene(text, "t.test", warnings, CourseOptions{LoadLimits{size_t{1} << 30}});
    EXPECT_EQ(scene->primitives.sphereCount(), 20000u);
}

TEST(CourseLoader, MemoryEstimateGrowsWithThePrimitives) {
    EXPECT_GT(Scene::estimateBytes(1000, 0), Scene::estimateBytes(100, 0));
    EXPECT_GT(Scene::estimateBytes(0, 10), Scene::estimateBytes(0, 1));
    // At least what the primitives and a BVH of the measured 57 bytes per triangle take.
    EXPECT_GE(Scene::estimateBytes(1000000, 0), size_t{1000000} * (36 + 57));
}

TEST(CourseLoader, Utf8ByteOrderMarkIsSkipped) {
    auto scene = parseOk("\xEF\xBB\xBFsize 32 16\n");
    EXPECT_EQ(scene->width, 32);
}

TEST(CourseLoader, PopTransformOnAnEmptyStackIsAnError) {
    expectError("popTransform\n", 1, 1,
                "popTransform without a matching pushTransform (--lenient ignores it)");
    expectError("pushTransform\npopTransform\n popTransform\n", 3, 2, "pushTransform");
}

TEST(CourseLoader, BadCamerasAreRejected) {
    expectError("camera 0 0 5 0 0 5 0 1 0 45\n", 1, 14, "from equals at");
    expectError("camera 0 0 5 0 0 0 0 0 1 45\n", 1, 20, "parallel");
    expectError("camera 0 0 5 0 0 0 0 0 0 45\n", 1, 20, "up vector");
    expectError("camera 0 0 5 0 0 0 0 1 0 0\n", 1, 26, "fovy");
    expectError("camera 0 0 5 0 0 0 0 1 0 180\n", 1, 26, "fovy");
    expectError("camera 0 0 5 0 0 0 0 1 0 -30\n", 1, 26, "fovy");
}

TEST(CourseLoader, NegativeRadiusShininessAttenuationAndZeroLightDirectionAreRejected) {
    expectError("sphere 0 0 0 -1\n", 1, 14, "radius");
    expectError("shininess -1\n", 1, 11, "shininess");
    expectError("attenuation 1 -0.1 0\n", 1, 15, "negative");
    expectError("attenuation 0 0 0\n", 1, 13, "zero");
    expectError("directional 0 0 0 1 1 1\n", 1, 13, "direction");
}

TEST(CourseLoader, MissingCameraIsReportedAtTheFirstCommand) {
    expectError("size 10 10\nsphere 0 0 0 1\n", 1, 1, "the scene has no camera (add 'camera");
    expectError("# first\n\n  size 10 10\n# last", 3, 3, "no camera");
}

TEST(CourseLoader, AFileWithoutCommandsSaysSo) {
    for (const char* text : {"", "\n\n", "# only a comment\n  \t\n# and another", "\xEF\xBB\xBF"})
        expectError(text, 0, 0, "the scene file has no commands");
}

// ---- warnings ---------------------------------------------------------------------------

TEST(CourseLoader, ZeroRadiusSphereIsSkippedWithAWarning) {
    std::unique_ptr<Scene> s;
    Diagnostic w = warningOf("sphere 0 0 0 0\nsphere 5 0 0 1\n", &s);
    EXPECT_EQ(w.loc.line, 1);
    EXPECT_EQ(w.loc.column, 14);
    EXPECT_EQ(w.loc.file, "t.test");
    EXPECT_EQ(s->primitives.sphereCount(), 1u);
    EXPECT_NEAR(s->primitives.bounds(0).lo.x, 4, 1e-5);
}

TEST(CourseLoader, SecondCameraReplacesTheFirstWithAWarning) {
    std::vector<Diagnostic> warnings;
    auto s = parse("camera 0 0 5 0 0 0 0 1 0 45\n\ncamera 1 1 1 0 0 0 0 1 0 60\n", warnings);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_EQ(warnings[0].loc.line, 3);
    EXPECT_EQ(warnings[0].loc.column, 1);
    EXPECT_THAT(warnings[0].message, HasSubstr("line 1"));
    EXPECT_EQ(s->camera->eye, Vec3(1, 1, 1));
    EXPECT_EQ(s->camera->fovyDegrees, 60);
}

TEST(CourseLoader, MoreVerticesThanMaxVertsWarnsOnce) {
    std::unique_ptr<Scene> s;
    Diagnostic w = warningOf(
        "maxverts 2\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nvertex 1 1 0\ntri 0 1 3\n", &s);
    EXPECT_EQ(w.loc.line, 4);
    EXPECT_EQ(w.loc.column, 1);
    EXPECT_THAT(w.message, HasSubstr("maxverts 2"));
    EXPECT_EQ(s->primitives.triangleCount(), 1u);  // the vertices are still usable
    Diagnostic n = warningOf(
        "maxvertnorms 1\nvertexnormal 0 0 0 0 0 1\nvertexnormal 1 0 0 0 0 1\n"
        "vertexnormal 0 1 0 0 0 1\ntrinormal 0 1 2\n");
    EXPECT_EQ(n.loc.line, 3);
    EXPECT_THAT(n.message, HasSubstr("maxvertnorms 1"));
}

TEST(CourseLoader, OutputWithAnUnsupportedExtensionWarnsButIsKept) {
    std::unique_ptr<Scene> s;
    Diagnostic w = warningOf("output scene.jpg\n", &s);
    EXPECT_EQ(w.loc.line, 1);
    EXPECT_EQ(w.loc.column, 8);
    EXPECT_THAT(w.message, HasSubstr("scene.jpg"));
    EXPECT_EQ(s->output, "scene.jpg");
    EXPECT_EQ(parseOk("output SCENE.PNG\n")->output, "SCENE.PNG");  // no warning
}

TEST(CourseLoader, ZeroLengthVertexNormalWarnsAndFallsBackToTheFaceNormal) {
    std::vector<Diagnostic> warnings;
    auto s = parse(
        "vertexnormal 0 0 0 0 0 0\nvertexnormal 1 0 0 0 0 0\nvertexnormal 0 1 0 0 0 0\n"
        "trinormal 0 1 2\n" +
            kCamera,
        warnings);
    ASSERT_EQ(warnings.size(), 3u);
    EXPECT_EQ(warnings[1].loc.line, 2);
    EXPECT_EQ(warnings[1].loc.column, 20);
    EXPECT_THAT(warnings[1].message, HasSubstr("zero length"));
    auto si = shoot(*s, {0.25, 0.25, 5}, {0, 0, -1});
    ASSERT_TRUE(si);
    expectNear(si->n, {0, 0, 1});
}

// ---- files ------------------------------------------------------------------------------

/// The diagnostic of the SceneError that loading `path` throws.
Diagnostic loadErrorOf(const std::string& path) {
    std::vector<Diagnostic> warnings;
    try {
        loadCourseScene(path, warnings);
    } catch (const SceneError& e) {
        return e.diagnostic();
    }
    ADD_FAILURE() << "no SceneError for " << path;
    return {};
}

class CourseLoaderFile : public ::testing::Test {
  protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() /
               ("glint-course-" + std::to_string(::getpid()) + "-" +
                ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }
    std::string write(const std::string& name, const std::string& text) {
        std::string path = (dir_ / name).string();
        std::ofstream(path, std::ios::binary) << text;
        return path;
    }
    fs::path dir_;
};

TEST_F(CourseLoaderFile, LoadsAFileAndNamesItInDiagnostics) {
    std::vector<Diagnostic> warnings;
    std::string good = write("good.test", "size 8 6\nsphere 0 0 0 0\n" + kCamera);
    auto s = loadCourseScene(good, warnings);
    EXPECT_EQ(s->width, 8);
    EXPECT_EQ(s->height, 6);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_EQ(warnings[0].loc.file, good);

    std::string bad = write("bad.test", "size 8 6\n\nsphere 0 0 0 -2\n");
    Diagnostic d = loadErrorOf(bad);
    EXPECT_EQ(d.loc.file, bad);
    EXPECT_EQ(d.loc.line, 3);
    EXPECT_EQ(d.loc.column, 14);
}

TEST_F(CourseLoaderFile, MissingFileIsASceneErrorWithoutALine) {
    std::string path = (dir_ / "missing.test").string();
    Diagnostic d = loadErrorOf(path);
    EXPECT_EQ(d.loc.file, path);
    EXPECT_EQ(d.loc.line, 0);
    EXPECT_THAT(d.message, HasSubstr("cannot read"));
}

TEST_F(CourseLoaderFile, DirectoryIsASceneErrorWithoutALine) {
    Diagnostic d = loadErrorOf(dir_.string());
    EXPECT_EQ(d.loc.line, 0);
    EXPECT_THAT(d.message, HasSubstr("directory"));
}

}  // namespace
}  // namespace glint
