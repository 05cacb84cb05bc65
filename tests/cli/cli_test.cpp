// The CLI as users meet it: exit codes (0 ok, 1 scene or render error, 2 usage error) and
// messages in the file:line:col form.

#include <gtest/gtest.h>

#include <filesystem>

#include "cli/cli_support.h"

namespace glint::test {
namespace {

namespace fs = std::filesystem;

TEST(Cli, BuiltInDemoSceneRendersToGlintPng) {
    std::string dir = freshDir("demo");
    CommandResult r = runGlint("-q --size 160x90", dir);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(fs::exists(fs::path(dir) / "glint.png"));
    EXPECT_GT(fs::file_size(fs::path(dir) / "glint.png"), 1000u);
}

TEST(Cli, UnknownFlagIsAUsageError) {
    CommandResult r = runGlint("--no-such-flag", freshDir("badflag"));
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_NE(r.err.find("no-such-flag"), std::string::npos) << r.err;
}

TEST(Cli, MalformedSceneReportsFileLineColumn) {
    std::string dir = freshDir("malformed");
    writeFile(dir + "/bad.test", "size 64 48\ncamera 0 0 5 0 0 0 0 1 0 45\nsphere 0 0 0\n");
    CommandResult r = runGlint("bad.test", dir);
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.err.find("bad.test:3:1: error: sphere expects 4 arguments"), std::string::npos)
        << r.err;
    EXPECT_FALSE(fs::exists(fs::path(dir) / "bad.png"));
}

}  // namespace
}  // namespace glint::test
