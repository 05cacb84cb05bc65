// What the course's own parser let pass and Glint reports: unknown commands and a popTransform
// on an empty stack (errors, or with `lenient` warnings said once per kind with a count), an
// empty file, a missing camera, and attenuation given after the point lights it cannot reach.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "unit/io/course/course_test_support.h"

namespace glint::test {
namespace {

/// Parses `body` followed by a camera leniently; returns the scene and fills `warnings`.
std::unique_ptr<Scene> parseLenient(const std::string& body, std::vector<Diagnostic>& warnings) {
    CourseOptions options;
    options.lenient = true;
    return parseCourseScene(body + kCamera, "t.test", warnings, options);
}

/// The error that parsing `text` (no camera added) leniently reports; the warnings before it
/// go to `warnings`.
Diagnostic lenientError(const std::string& text, std::vector<Diagnostic>& warnings) {
    CourseOptions options;
    options.lenient = true;
    try {
        parseCourseScene(text, "t.test", warnings, options);
    } catch (const SceneError& e) {
        return e.diagnostic();
    }
    ADD_FAILURE() << "no SceneError for:\n" << text;
    return {};
}

std::vector<std::string> formatted(const std::vector<Diagnostic>& warnings) {
    std::vector<std::string> out;
    for (const Diagnostic& d : warnings) out.push_back(d.format("warning"));
    return out;
}

TEST(CourseStrict, AnUnknownCommandSaysThatLenientSkipsIt) {
    expectError("frobnicate 1 2\n", 1, 1,
                "unknown command 'frobnicate' (--lenient skips unknown commands)");
    Diagnostic d = errorOf("sphre 0 0 0 1\n");
    EXPECT_EQ(d.message,
              "unknown command 'sphre' (--lenient skips unknown commands); did you mean "
              "'sphere'?");
}

TEST(CourseLenient, UnknownCommandsAreSkippedWithOneWarningPerNameAndACount) {
    std::vector<Diagnostic> w;
    auto scene = parseLenient(
        "size 20 10\narea 1 2 3\nsphere 0 0 0 1\n  area\nsphre 0 0 0 1\narea 4\nsphere 0 0 2 1\n",
        w);
    EXPECT_THAT(formatted(w),
                ::testing::ElementsAre(
                    "t.test:2:1: warning: unknown command 'area' skipped (3 times; first here)",
                    "t.test:5:1: warning: unknown command 'sphre' skipped; did you mean "
                    "'sphere'?"));
    // Everything else is read.
    EXPECT_EQ(scene->width, 20);
    EXPECT_EQ(scene->primitives.sphereCount(), 2u);
    EXPECT_TRUE(scene->camera);
}

TEST(CourseLenient, AStrayBracketIsAnUnknownCommand) {
    std::vector<Diagnostic> w;
    auto scene = parseLenient("[\nsphere 0 0 0 1\n]\n", w);
    EXPECT_THAT(formatted(w), ::testing::ElementsAre("t.test:1:1: warning: unknown command '[' "
                                                     "skipped",
                                                     "t.test:3:1: warning: unknown command ']' "
                                                     "skipped"));
    EXPECT_EQ(scene->primitives.sphereCount(), 1u);
    expectError("[\n", 1, 1, "unknown command '[' (--lenient skips unknown commands)");
}

TEST(CourseLenient, APopOnAnEmptyStackIsIgnoredWithOneWarning) {
    std::vector<Diagnostic> w;
    auto scene = parseLenient(
        "translate 5 0 0\npopTransform\npushTransform\npopTransform\n popTransform\n"
        "sphere 0 0 0 1\n",
        w);
    EXPECT_THAT(formatted(w),
                ::testing::ElementsAre("t.test:2:1: warning: popTransform without a matching "
                                       "pushTransform ignored (2 times; first here)"));
    // The transform stays what it was: the sphere is at x = 5.
    ASSERT_EQ(scene->primitives.sphereCount(), 1u);
    EXPECT_NEAR(scene->primitives.bounds(0).lo.x, 4, 1e-5);
}

TEST(CourseLenient, OtherErrorsStayErrors) {
    std::vector<Diagnostic> w;
    EXPECT_EQ(lenientError("area\nsphere 0 0 0\n", w).format("error"),
              "t.test:2:1: error: sphere expects 4 arguments (x y z radius), got 3");
    EXPECT_EQ(w.size(), 1u);  // the warnings so far are kept
}

TEST(CourseScene, AnEmptyFileAndAMissingCameraPointInsideTheFile) {
    EXPECT_EQ(errorOf("# nothing here\n\n").format("error"),
              "t.test: error: the scene file has no commands");
    EXPECT_EQ(errorOf("\n  size 10 10\nsphere 0 0 0 1\n").format("error"),
              "t.test:2:3: error: the scene has no camera (add 'camera fromx fromy fromz atx aty "
              "atz upx upy upz fovy')");
    // With lenient, a file of unknown commands has commands, and no camera.
    std::vector<Diagnostic> w;
    Diagnostic d = lenientError("# c\narea\n", w);
    EXPECT_EQ(d.loc.line, 2);
    EXPECT_THAT(d.message, ::testing::HasSubstr("no camera"));
}

TEST(CourseAttenuation, AfterAPointLightItWarnsThatItReachesOnlyLaterOnes) {
    std::unique_ptr<Scene> scene;
    Diagnostic d = warningOf("point 0 1 0 1 1 1\nattenuation 0 0 1\npoint 0 2 0 1 1 1\n", &scene);
    EXPECT_EQ(d.format("warning"),
              "t.test:2:1: warning: attenuation applies only to point lights declared after it: "
              "the one on line 1 keeps its own (reported once)");
    ASSERT_EQ(scene->lights.size(), 2u);
    EXPECT_EQ(scene->lights[0].attenuation, Vec3(1, 0, 0));
    EXPECT_EQ(scene->lights[1].attenuation, Vec3(0, 0, 1));
    // Several lights before it; said once however often attenuation changes.
    d = warningOf(
        "directional 0 1 0 1 1 1\npoint 0 1 0 1 1 1\npoint 0 2 0 1 1 1\nattenuation 0 1 0\n"
        "attenuation 0 0 1\n");
    EXPECT_EQ(d.format("warning"),
              "t.test:4:1: warning: attenuation applies only to point lights declared after it: "
              "the 2 declared before it, from line 2, keep theirs (reported once)");
}

TEST(CourseAttenuation, BeforeThePointLightsOrUnchangedItIsSilent) {
    parseOk("attenuation 1 0.1 0.05\npoint 0 1 0 1 1 1\npoint 0 2 0 1 1 1\n");
    parseOk("directional 0 1 0 1 1 1\nattenuation 0 0 1\n");               // not a point light
    parseOk("point 0 1 0 1 1 1\nattenuation 1 0 0\npoint 0 2 0 1 1 1\n");  // the same value
}

}  // namespace
}  // namespace glint::test
