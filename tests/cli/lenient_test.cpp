// `glint --lenient`: scenes written for the course's own parser, which skipped unknown commands
// and a popTransform with nothing pushed, render with one warning per kind of problem.

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "cli/cli_support.h"
#include "glint/io/image/image_io.h"

namespace glint::test {
namespace {

namespace fs = std::filesystem;

/// A scene as other people wrote them for the course: commands Glint does not know, a stray
/// bracket, and one popTransform too many.
const std::string kSloppyScene =
    "size 32 24\n"
    "camera 0 0 5 0 0 0 0 1 0 45\n"
    "ambient 0.5 0.5 0.5\n"
    "area 1 1 1\n"
    "[\n"
    "sphere 0 0 0 1\n"
    "popTransform\n"
    "area 2 2 2\n"
    "]\n";

TEST(CliLenient, SkipsUnknownCommandsAndAStrayPopWithOneWarningEachAndRenders) {
    std::string dir = freshDir("lenient");
    writeFile(dir + "/s.test", kSloppyScene);
    CommandResult r = runGlint("-q --lenient s.test", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(r.err,
              "s.test:4:1: warning: unknown command 'area' skipped (2 times; first here)\n"
              "s.test:5:1: warning: unknown command '[' skipped\n"
              "s.test:7:1: warning: popTransform without a matching pushTransform ignored\n"
              "s.test:9:1: warning: unknown command ']' skipped\n");
    Image8 img = readImage8(dir + "/s.png", 3);
    EXPECT_EQ(img.width, 32);
    EXPECT_EQ(img.at(16, 12, 0), 127);  // the sphere, ambient 0.5, in the middle
    EXPECT_EQ(img.at(0, 0, 0), 0);      // the background
}

TEST(CliLenient, WithoutItTheFirstProblemIsAnErrorThatMentionsIt) {
    std::string dir = freshDir("strict");
    writeFile(dir + "/s.test", kSloppyScene);
    CommandResult r = runGlint("s.test", dir);
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_EQ(r.err,
              "s.test:4:1: error: unknown command 'area' (--lenient skips unknown commands)\n");
    EXPECT_FALSE(fs::exists(dir + "/s.png"));
}

}  // namespace
}  // namespace glint::test
