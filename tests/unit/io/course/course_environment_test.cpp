// The `environment FILE [scale] [rotation]` command: the map is read relative to the scene
// file, scaled and rotated, replaces the background for rays that miss (camera and mirror
// rays under the Whitted integrator); every error names the line, the column and the reason.

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <stb_image_write.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "glint/io/course/course_loader.h"
#include "glint/io/image/exr.h"
#include "glint/io/image/image_io.h"
#include "glint/render/integrators/whitted.h"
#include "unit/io/course/course_test_support.h"
#include "unit/test_support.h"

namespace glint {
namespace {

using test::expectNear;
using test::kCamera;
using ::testing::HasSubstr;

class CourseEnvironment : public test::TempDirTest {
  protected:
    void SetUp() override {
        TempDirTest::SetUp();
        std::filesystem::create_directory(path("maps"));
        // 4 x 2 texels: the top row (0.5, 1, 2), the bottom row (4, 2, 1); exact in RGBE.
        std::vector<float> rgb;
        for (int y = 0; y < 2; ++y)
            for (int x = 0; x < 4; ++x)
                for (float v :
                     y == 0 ? std::vector<float>{0.5f, 1, 2} : std::vector<float>{4, 2, 1})
                    rgb.push_back(v);
        ASSERT_TRUE(stbi_write_hdr(path("maps/sky.hdr").c_str(), 4, 2, 3, rgb.data()));
        Film film(4, 2);
        for (int x = 0; x < 4; ++x) {
            film.at(x, 0) = Vec3(0.5, 1, 2);
            film.at(x, 1) = Vec3(4, 2, 1);
        }
        std::ofstream(path("maps/sky.exr"), std::ios::binary) << encodeExr(film);
    }

    /// Parses `body` and a camera as the file scene.test in the test's directory.
    std::unique_ptr<Scene> parseHere(const std::string& body,
                                     std::vector<Diagnostic>* warnings = nullptr,
                                     const LoadLimits& limits = {}) {
        std::vector<Diagnostic> w;
        auto scene = parseCourseScene(body + kCamera, path("scene.test"), w, CourseOptions{limits});
        if (warnings)
            *warnings = w;
        else
            EXPECT_TRUE(w.empty()) << w.front().format("warning");
        return scene;
    }

    Diagnostic errorHere(const std::string& body, const LoadLimits& limits = {}) {
        std::vector<Diagnostic> w;
        try {
            parseCourseScene(body + kCamera, path("scene.test"), w, CourseOptions{limits});
        } catch (const SceneError& e) {
            EXPECT_EQ(e.diagnostic().loc.file, path("scene.test"));
            return e.diagnostic();
        }
        ADD_FAILURE() << "no error for:\n" << body;
        return {};
    }
};

TEST(CourseEnvironmentCommand, IsAmongTheCommandNames) {
    auto names = courseCommandNames();
    EXPECT_NE(std::find(names.begin(), names.end(), "environment"), names.end());
}

TEST_F(CourseEnvironment, ReadsHdrAndExrRelativeToTheSceneFile) {
    for (const char* file : {"maps/sky.hdr", "maps/sky.exr"}) {
        auto s = parseHere(std::string("environment ") + file + "\n");
        ASSERT_TRUE(s->environment) << file;
        const EnvironmentMap& env = *s->environment;
        EXPECT_EQ(env.width(), 4);
        EXPECT_EQ(env.height(), 2);
        EXPECT_EQ(env.scale(), 1);
        EXPECT_EQ(env.rotationDegrees(), 0);
        // Up sees the top row, down the bottom one.
        expectNear(env.eval({0, 1, 0}), {0.5, 1, 2});
        expectNear(env.eval({0.1, -1, 0.2}), {4, 2, 1});
        expectNear(s->backgroundRadiance({0, 1, 0}), {0.5, 1, 2});
    }
}

TEST_F(CourseEnvironment, ScaleAndRotationAreApplied) {
    auto s = parseHere("environment maps/sky.hdr 2.5 -30\n");
    ASSERT_TRUE(s->environment);
    EXPECT_EQ(s->environment->scale(), 2.5);
    EXPECT_EQ(s->environment->rotationDegrees(), -30);
    expectNear(s->environment->eval({0, 1, 0}), {1.25, 2.5, 5});
    s = parseHere("environment maps/sky.hdr 0\n");
    expectNear(s->environment->eval({0, 1, 0}), {0, 0, 0});
    // An absolute path is used as it is.
    s = parseHere("environment " + path("maps/sky.exr") + " 1 1e6\n");
    EXPECT_EQ(s->environment->rotationDegrees(), 1e6);
}

TEST_F(CourseEnvironment, TheMapIsSeenByCameraRaysAndInMirrors) {
    // Without geometry every camera ray sees the map; a mirror floor shows it too.
    auto s = parseHere("environment maps/sky.hdr\nbackground 9 9 9\n");
    s->prepare();
    WhittedIntegrator whitted(*s);
    RayCounts counts;
    expectNear(whitted.radiance({{0, 0, 0}, normalize(Vec3(0.2, 1, 0.1))}, 0, counts), {0.5, 1, 2});
    expectNear(whitted.radiance({{0, 0, 0}, {0, -1, 0}}, 0, counts), {4, 2, 1});
    auto mirror = parseHere(
        "environment maps/sky.hdr\nambient 0 0 0\nspecular 0.5 0.5 0.5\n"
        "plane 0 -1 0 0 1 0\n");
    mirror->prepare();
    WhittedIntegrator mirrored(*mirror);
    // Looking down at the mirror: the reflection looks up.
    expectNear(mirrored.radiance({{0, 0, 0}, {0, -1, 0}}, 0, counts), {0.25, 0.5, 1});
}

TEST_F(CourseEnvironment, ASecondEnvironmentReplacesTheFirstWithAWarning) {
    std::vector<Diagnostic> warnings;
    auto s = parseHere("environment maps/sky.hdr\n\nenvironment maps/sky.exr 3\n", &warnings);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_EQ(warnings[0].loc.line, 3);
    EXPECT_EQ(warnings[0].loc.column, 1);
    EXPECT_EQ(warnings[0].message, "a second environment replaces the one on line 1");
    EXPECT_EQ(s->environment->scale(), 3);
}

TEST_F(CourseEnvironment, BadTexelsAreReportedOnce) {
    Film film(2, 1);
    film.at(0, 0) = Vec3(-1, std::nan(""), 2);
    film.at(1, 0) = Vec3(1, 1, 1);
    std::ofstream(path("bad.exr"), std::ios::binary) << encodeExr(film);
    std::vector<Diagnostic> warnings;
    auto s = parseHere("environment bad.exr\n", &warnings);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_EQ(warnings[0].loc.column, 13);
    EXPECT_EQ(warnings[0].message,
              "environment map 'bad.exr' has 2 values that are negative, NaN or beyond 1e30: "
              "negative and NaN values read as 0, larger ones as 1e30");
    EXPECT_EQ(s->environment->texel(0, 0), Vec3(0, 0, 2));
}

TEST_F(CourseEnvironment, ErrorsNameTheLineColumnAndReason) {
    Diagnostic d = errorHere("size 10 10\nenvironment maps/nowhere.hdr\n");
    EXPECT_EQ(d.loc.line, 2);
    EXPECT_EQ(d.loc.column, 13);
    EXPECT_EQ(d.message, "cannot read environment map '" + path("maps/nowhere.hdr") +
                             "': No such file or directory");
    std::ofstream(path("maps/notes.txt")) << "not an image\n";
    EXPECT_EQ(errorHere("environment maps/notes.txt\n").message,
              "cannot read environment map '" + path("maps/notes.txt") +
                  "': not a Radiance HDR (.hdr) or OpenEXR (.exr) file");
    Film film(2, 2);
    writeImage(path("maps/ldr.png"), film);
    EXPECT_THAT(errorHere("environment maps/ldr.png\n").message,
                HasSubstr("it is an 8-bit image, not a high-dynamic-range one"));
    LoadLimits tight;
    tight.memoryBytes = 100;
    EXPECT_THAT(errorHere("environment maps/sky.hdr\n", tight).message,
                HasSubstr("reading and sampling it needs about"));

    Diagnostic scale = errorHere("environment maps/sky.hdr -1\n");
    EXPECT_EQ(scale.loc.column, 26);
    EXPECT_EQ(scale.message, "environment scale must not be negative, got '-1'");
    EXPECT_EQ(errorHere("environment maps/sky.hdr nan\n").message,
              "expected a finite number, got 'nan'");
    EXPECT_EQ(errorHere("environment maps/sky.hdr 1e39\n").message, "number '1e39' is too large");
    Diagnostic rotation = errorHere("environment maps/sky.hdr 1 inf\n");
    EXPECT_EQ(rotation.loc.column, 28);
    EXPECT_EQ(rotation.message, "expected a finite number, got 'inf'");
    EXPECT_EQ(errorHere("environment maps/sky.hdr 1 east\n").message,
              "expected a number, got 'east'");
    EXPECT_EQ(errorHere("environment\n").message,
              "environment expects 1 to 3 arguments (file [scale] [rotation]), got 0");
    Diagnostic extra = errorHere("environment maps/sky.hdr 1 2 3\n");
    EXPECT_EQ(extra.loc.column, 30);
    EXPECT_EQ(extra.message,
              "environment expects 1 to 3 arguments (file [scale] [rotation]), got 4");

    LoadLimits noFiles;
    noFiles.readFiles = false;
    EXPECT_EQ(errorHere("environment maps/sky.hdr\n", noFiles).message,
              "environment map 'maps/sky.hdr' is not read: reading files is off");
}

}  // namespace
}  // namespace glint
