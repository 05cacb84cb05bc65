// The shape extensions of the scene format: plane, box, cylinder, cone, disk, polygon
// (docs/scene-format.md). Every command, under transforms, and every error with its position.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <string>

#include "glint/io/course/course_loader.h"
#include "unit/test_support.h"

namespace glint {
namespace {

using test::expectNear;
using ::testing::HasSubstr;

const std::string kCamera = "camera 0 0 10 0 0 0 0 1 0 45\n";

std::unique_ptr<Scene> parseOk(const std::string& body) {
    std::vector<Diagnostic> warnings;
    auto scene = parseCourseScene(body + kCamera, "s.test", warnings);
    EXPECT_TRUE(warnings.empty()) << warnings.front().format("warning");
    return scene;
}

void expectError(const std::string& body, int line, int column, const std::string& message) {
    std::vector<Diagnostic> warnings;
    try {
        parseCourseScene(body + kCamera, "s.test", warnings);
        ADD_FAILURE() << "no SceneError for:\n" << body;
    } catch (const SceneError& e) {
        EXPECT_EQ(e.diagnostic().loc.file, "s.test");
        EXPECT_EQ(e.diagnostic().loc.line, line) << body;
        EXPECT_EQ(e.diagnostic().loc.column, column) << body;
        EXPECT_THAT(e.diagnostic().message, HasSubstr(message)) << body;
    }
}

/// The closest hit of the ray from `origin` along `dir`, with its shading data.
std::optional<SurfaceInteraction> shoot(Scene& scene, const Vec3& origin, const Vec3& dir) {
    if (!scene.prepared()) scene.prepare();
    Ray ray{origin, normalize(dir)};
    Hit hit;
    if (!scene.bvh().intersect(ray, hit)) return std::nullopt;
    return scene.primitives.interaction(ray, hit);
}

void expectHit(Scene& scene, const Vec3& origin, const Vec3& dir, const Vec3& p, const Vec3& n) {
    auto si = shoot(scene, origin, dir);
    ASSERT_TRUE(si) << "nothing hit from " << origin.x << " " << origin.y << " " << origin.z;
    expectNear(si->p, p, 1e-9);
    expectNear(si->n, n, 1e-9);
}

// ---- Each command under the current transform, with the current material ----------------

TEST(CourseShapes, PlaneThroughAPointWithAnyLengthNormalUnderTheTransform) {
    auto s = parseOk(
        "diffuse 1 0 0\npushTransform\ntranslate 0 2 0\nrotate 1 0 0 90\n"
        "plane 0 0 0 0 0 5\npopTransform\n");
    ASSERT_EQ(s->primitives.planeCount(), 1u);
    // (0, 0, 1) rotated 90 degrees about x is (0, -1, 0); the plane is y = 2.
    expectHit(*s, {3, -5, 1}, {0, 1, 0}, {3, 2, 1}, {0, -1, 0});
    auto si = shoot(*s, {0, 5, 0}, {0, -1, 0});  // from the other side: the same normal
    ASSERT_TRUE(si);
    expectNear(si->n, {0, -1, 0});
    EXPECT_EQ(s->materials.at(si->material).diffuse, Vec3(1, 0, 0));
    EXPECT_FALSE(shoot(*s, {0, 5, 0}, {1, 0, 0}));  // parallel
    EXPECT_TRUE(s->bvh().bounds().empty());         // not part of the scene bounds
}

TEST(CourseShapes, BoxFromTwoCornersInAnyOrderUnderNonUniformScale) {
    auto s = parseOk("scale 2 1 1\nbox 1 1 1 -1 -1 -1\n");
    ASSERT_EQ(s->primitives.shapeCount(ShapeKind::Box), 1u);
    expectHit(*s, {10, 0.5, 0.5}, {-1, 0, 0}, {2, 0.5, 0.5}, {1, 0, 0});
    expectHit(*s, {0, 0, 0}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1});  // from inside
}

TEST(CourseShapes, CylinderBetweenTwoEndCentres) {
    auto s = parseOk("cylinder 0 0 -1 0 0 1 0.5\n");
    ASSERT_EQ(s->primitives.shapeCount(ShapeKind::Cylinder), 1u);
    expectHit(*s, {0, 0, 5}, {0, 0, -1}, {0, 0, 1}, {0, 0, 1});
    expectHit(*s, {5, 0, 0}, {-1, 0, 0}, {0.5, 0, 0}, {1, 0, 0});
}

TEST(CourseShapes, ConeWithEitherEndPointedAndFrustums) {
    auto pointed = parseOk("cone 0 0 0 0 0 0 2 1\n");  // apex at the origin, base at z = 2
    ASSERT_EQ(pointed->primitives.shapeCount(ShapeKind::Cone), 1u);
    expectHit(*pointed, {0, 0, 5}, {0, 0, -1}, {0, 0, 2}, {0, 0, 1});
    expectHit(*pointed, {-5, 0, 1}, {1, 0, 0}, {-0.5, 0, 1}, normalize(Vec3(-1, 0, -0.5)));
    auto frustum = parseOk("cone 0 0 0 1 0 0 2 0.5\n");
    expectHit(*frustum, {0, 0, 5}, {0, 0, -1}, {0, 0, 2}, {0, 0, 1});
}

TEST(CourseShapes, DiskWithItsNormalUnderRotation) {
    auto s = parseOk("rotate 0 1 0 90\ndisk 0 0 0 0 0 1 2\n");
    ASSERT_EQ(s->primitives.shapeCount(ShapeKind::Disk), 1u);
    // (0, 0, 1) rotated 90 degrees about y is (1, 0, 0).
    expectHit(*s, {5, 1, 1}, {-1, 0, 0}, {0, 1, 1}, {1, 0, 0});
    EXPECT_FALSE(shoot(*s, {5, 2.5, 0}, {-1, 0, 0}));
}

TEST(CourseShapes, PolygonIsTriangulatedWithTheVertexListAndTheCurrentTransform) {
    const std::string lShape =
        "vertex 0 0 0\nvertex 3 0 0\nvertex 3 1 0\nvertex 1 1 0\nvertex 1 3 0\nvertex 0 3 0\n";
    auto s = parseOk(lShape + "translate 0 0 -1\npolygon 0 1 2 3 4 5\n");
    EXPECT_EQ(s->primitives.triangleCount(), 4u);
    expectHit(*s, {2.5, 0.5, 5}, {0, 0, -1}, {2.5, 0.5, -1}, {0, 0, 1});
    expectHit(*s, {0.5, 2.5, 5}, {0, 0, -1}, {0.5, 2.5, -1}, {0, 0, 1});
    EXPECT_FALSE(shoot(*s, {2, 2, 5}, {0, 0, -1}));  // the notch
    // Clockwise: faces down, like tri.
    auto down = parseOk(lShape + "polygon 5 4 3 2 1 0\n");
    expectHit(*down, {0.5, 0.5, 5}, {0, 0, -1}, {0.5, 0.5, 0}, {0, 0, -1});
    // A mirroring transform turns the order, and the normal with it, as for tri.
    auto mirrored = parseOk(lShape + "scale -1 1 1\npolygon 0 1 2 3 4 5\n");
    expectHit(*mirrored, {-0.5, 0.5, 5}, {0, 0, -1}, {-0.5, 0.5, 0}, {0, 0, -1});
    auto tri = parseOk(lShape + "scale -1 1 1\ntri 0 1 2\n");
    expectHit(*tri, {-2.9, 0.5, 5}, {0, 0, -1}, {-2.9, 0.5, 0}, {0, 0, -1});
}

TEST(CourseShapes, PolygonWithCollinearVerticesAndTheLargestVertexCount) {
    auto s = parseOk(
        "vertex 0 0 0\nvertex 1 0 0\nvertex 2 0 0\nvertex 2 1 0\nvertex 0 1 0\n"
        "polygon 0 1 2 3 4\n");
    EXPECT_EQ(s->primitives.triangleCount(), 3u);
    std::string text;
    const double pi = std::acos(-1.0);
    // Appended piece by piece: GCC 12 warns falsely on "literal" + std::string.
    for (int i = 0; i < 1024; ++i)
        text.append("vertex ")
            .append(std::to_string(std::cos(2 * pi * i / 1024)))
            .append(" ")
            .append(std::to_string(std::sin(2 * pi * i / 1024)))
            .append(" 0\n");
    text += "polygon";
    for (int i = 0; i < 1024; ++i) text.append(" ").append(std::to_string(i));
    auto big = parseOk(text + "\n");
    EXPECT_EQ(big->primitives.triangleCount(), 1022u);
}

TEST(CourseShapes, ShapesCountInTheMemoryEstimate) {
    std::string text = kCamera + "vertex 0 0 0\nvertex 1 0 0\nvertex 1 1 0\nvertex 0 1 0\n";
    for (int i = 0; i < 4000; ++i) text += "cylinder 0 0 0 0 0 1 1\npolygon 0 1 2 3\n";
    std::vector<Diagnostic> warnings;
    try {
        parseCourseScene(text, "m.test", warnings, CourseOptions{LoadLimits{1 << 20}});
        ADD_FAILURE() << "no SceneError";
    } catch (const SceneError& e) {
        EXPECT_THAT(e.diagnostic().message, HasSubstr("(8000 triangles, 0 spheres, 4000 other"));
    }
    auto scene =
        parseCourseScene(text, "m.test", warnings, CourseOptions{LoadLimits{size_t{1} << 30}});
    EXPECT_EQ(scene->primitives.shapeCount(), 4000u);
    EXPECT_EQ(scene->primitives.triangleCount(), 8000u);
    EXPECT_GT(Scene::estimateBytes(0, 0, 10), Scene::estimateBytes(0, 0, 1));
}

// ---- Errors -------------------------------------------------------------------------------

TEST(CourseShapes, ArgumentCountsAndNumbersAreCheckedLikeEveryCommand) {
    expectError("box 0 0 0 1 1\n", 1, 1, "box expects 6 arguments (x0 y0 z0 x1 y1 z1), got 5");
    expectError("cylinder 0 0 0 0 0 1 1 1\n", 1, 24, "cylinder expects 7 arguments");
    expectError("cone 0 0 0 1 0 0 1\n", 1, 1, "cone expects 8 arguments (x0 y0 z0 r0 x1 y1 z1 r1)");
    expectError("disk 0 0 0 0 0 1\n", 1, 1, "disk expects 7 arguments (cx cy cz nx ny nz radius)");
    expectError("plane 0 0 0 0 1\n", 1, 1, "plane expects 6 arguments (px py pz nx ny nz)");
    expectError("vertex 0 0 0\nvertex 1 0 0\npolygon 0 1\n", 3, 1,
                "polygon expects 3 to 1024 arguments (v1 v2 v3 ...), got 2");
    std::string many = "polygon";
    for (int i = 0; i < 1025; ++i) many += " 0";
    expectError(many + "\n", 1, 8 + 2 * 1024 + 1, "polygon expects 3 to 1024 arguments");
    expectError("box 0 0 0 nan 1 1\n", 1, 11, "expected a finite number, got 'nan'");
    expectError("cone 0 0 0 1e39 0 0 1 1\n", 1, 12, "number '1e39' is too large");
    expectError("disk 0 0 0 0 0 1 x\n", 1, 18, "expected a number, got 'x'");
}

TEST(CourseShapes, DegenerateShapesPointAtTheArgumentAtFault) {
    expectError("box 0 0 0 1 0 1\n", 1, 13,
                "box has zero extent along y: both corners have y = '0'");
    expectError("cylinder 1 2 3 1 2 3 1\n", 1, 16, "the cylinder's end points coincide");
    expectError("cylinder 0 0 0 0 0 1 0\n", 1, 22, "cylinder radius must be positive, got '0'");
    expectError("cylinder 0 0 0 0 0 1 -2\n", 1, 22, "cylinder radius must be positive, got '-2'");
    expectError("cone 0 0 0 -1 0 0 1 1\n", 1, 12, "cone radius must not be negative, got '-1'");
    expectError("cone 0 0 0 1 0 0 1 -1\n", 1, 20, "cone radius must not be negative, got '-1'");
    expectError("cone 0 0 0 0 0 0 1 0\n", 1, 12, "cone radii must not both be zero");
    expectError("cone 0 0 1 1 0 0 1 0\n", 1, 14, "the cone's end points coincide");
    expectError("disk 0 0 0 0 0 0 1\n", 1, 12, "disk normal must not be zero");
    expectError("disk 0 0 0 0 0 1 0\n", 1, 18, "disk radius must be positive, got '0'");
    expectError("plane 0 0 0 0 0 0\n", 1, 13, "plane normal must not be zero");
}

TEST(CourseShapes, TransformsAndCoordinateLimitsAreCheckedAsForSpheres) {
    expectError("scale 1e10 1e10 1e10\nbox 0 0 0 1e9 1 1\n", 2, 1,
                "the box reaches beyond the supported coordinate range (1e18)");
    expectError("cylinder 0 0 0 0 0 1 1e-20\n", 1, 1,
                "the cylinder is too thin: a dimension is below 1e-18 after the transform");
    expectError("scale 1e-200 1e-200 1e-200\ncone 0 0 0 1e-120 0 0 1e-120 0\n", 2, 1,
                "the cone is degenerate after the transform");
    expectError("translate 1e18 0 0\nplane 1e18 0 0 0 1 0\n", 2, 7,
                "the plane's point lies beyond the supported coordinate range (1e18)");
    expectError("scale 1e-300 1 1\nplane 0 0 0 3e38 0 0\n", 2, 13,
                "the plane's normal cannot be normalised after the transform");
    // A singular transform is reported at the first shape that uses it, as for spheres.
    expectError("scale 1e-200 1 1\nscale 1e-200 1 1\ndisk 0 0 0 0 0 1 1\n", 3, 1,
                "the current transform is singular or not finite");
}

TEST(CourseShapes, PolygonErrorsNameTheVertexAtFault) {
    const std::string square = "vertex 0 0 0\nvertex 1 0 0\nvertex 1 1 0\nvertex 0 1 0\n";
    expectError(square + "polygon 0 1 2 4\n", 5, 15,
                "vertex index '4' is out of range: 4 vertices are defined (0 to 3)");
    expectError("polygon 0 1 2\n", 1, 9,
                "vertex index '0' is out of range: no vertex has been defined yet");
    expectError(square + "polygon 0 1 -2\n", 5, 13, "integer '-2' is out of range");
    expectError(square + "polygon 0 1 2 1\n", 5, 15,
                "vertex index '1' appears twice in the polygon");
    expectError(square + "vertex 1 1 0\npolygon 0 1 2 4\n", 6, 15,
                "polygon vertex '4' is at the same position as vertex '2'");
    expectError("vertex 0 0 0\nvertex 1 1 1\nvertex 2 2 2\npolygon 0 1 2\n", 4, 1,
                "the polygon has zero area: its vertices lie on one line");
    // A house whose roof top is lifted off the plane of the walls.
    expectError(square + "vertex 0.5 1.5 0.5\npolygon 0 1 2 4 3\n", 6, 15,
                "the polygon is not planar: vertex '4' lies off its plane by");
    expectError("vertex 0 0 0\nvertex 2 2 0\nvertex 2 0 0\nvertex 0 1 0\npolygon 0 1 2 3\n", 5, 13,
                "the polygon's edges cross: the edge from vertex '2' to '3' meets the edge from "
                "vertex '0' to '1'");
}

TEST(CourseShapes, CommandNamesIncludeTheShapes) {
    auto names = courseCommandNames();
    for (const char* name : {"plane", "box", "cylinder", "cone", "disk", "polygon"})
        EXPECT_NE(std::find(names.begin(), names.end(), name), names.end()) << name;
}

}  // namespace
}  // namespace glint
