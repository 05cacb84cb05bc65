#include "cli/cli_support.h"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace glint::test {

namespace fs = std::filesystem;

namespace {

CommandResult runProgram(const std::string& binary, const std::string& args,
                         const std::string& workDir) {
    fs::create_directories(workDir);
    fs::path out = fs::path(workDir) / ".stdout", err = fs::path(workDir) / ".stderr";
    std::string cmd = "cd '" + workDir + "' && '" + binary + "' " + args + " >'" + out.string() +
                      "' 2>'" + err.string() + "' </dev/null";
    int status = std::system(cmd.c_str());
    CommandResult r;
    r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.out = readBytes(out.string());
    r.err = readBytes(err.string());
    fs::remove(out);
    fs::remove(err);
    return r;
}

}  // namespace

CommandResult runGlint(const std::string& args, const std::string& workDir) {
    return runProgram(GLINT_BINARY, args, workDir);
}

CommandResult runImgdiff(const std::string& args, const std::string& workDir) {
    return runProgram(GLINT_IMGDIFF_BINARY, args, workDir);
}

std::string readBytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

bool contains(const std::string& haystack, const std::string& needle) {
    return haystack.find(needle) != std::string::npos;
}

void writeFile(const std::string& path, const std::string& text) {
    fs::create_directories(fs::path(path).parent_path());
    std::ofstream(path, std::ios::binary) << text;
}

namespace {

/// The directories freshDir made in this process, removed when it ends unless a test failed
/// (then they are kept to look at). A full run made 177 and left them all behind.
struct MadeDirs {
    std::vector<fs::path> dirs;
    ~MadeDirs() {
        if (::testing::UnitTest::GetInstance()->Failed()) return;
        for (const fs::path& d : dirs) {
            std::error_code ignored;
            fs::remove_all(d, ignored);
        }
    }
};

MadeDirs& madeDirs() {
    // Made after gtest's UnitTest (freshDir runs inside a test), so destroyed before it.
    static MadeDirs made;
    return made;
}

}  // namespace

std::string freshDir(const std::string& name) {
    fs::path dir =
        fs::temp_directory_path() / ("glint-cli-" + std::to_string(::getpid()) + "-" + name);
    fs::remove_all(dir);
    fs::create_directories(dir);
    madeDirs().dirs.push_back(dir);
    return dir.string();
}

}  // namespace glint::test
