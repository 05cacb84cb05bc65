// Interrupts (issue 4): SIGINT or SIGTERM during a render stops it promptly, writes the finished
// part (marked partial on stderr) and exits 128 + the signal; a second signal leaves at once.
// The output file is never truncated or corrupt.

#include <fcntl.h>
#include <gtest/gtest.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "cli/cli_support.h"
#include "glint/core/error.h"
#include "glint/io/image/image_io.h"

extern char** environ;

namespace glint::test {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

/// glint running in the background, its stderr going to a file.
class Running {
  public:
    Running(const std::vector<std::string>& args, const std::string& dir) : err_(dir + "/err") {
        std::vector<char*> argv;
        std::string binary = GLINT_BINARY;
        argv.push_back(binary.data());
        for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
        argv.push_back(nullptr);
        posix_spawn_file_actions_t actions;
        posix_spawn_file_actions_init(&actions);
        posix_spawn_file_actions_addopen(&actions, 2, err_.c_str(), O_WRONLY | O_CREAT | O_TRUNC,
                                         0644);
        posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
        EXPECT_EQ(posix_spawn(&pid_, binary.c_str(), &actions, nullptr, argv.data(), environ), 0);
        posix_spawn_file_actions_destroy(&actions);
    }

    void signal(int sig) { ::kill(pid_, sig); }

    /// Waits until glint catches `sig` (its handler is installed), as /proc shows: a signal
    /// sent earlier would kill it by the default action. Start-up is slow under sanitizers.
    bool waitForHandler(int sig) {
        auto start = Clock::now();
        while (Clock::now() - start < std::chrono::seconds(10)) {
            std::ifstream status("/proc/" + std::to_string(pid_) + "/status");
            for (std::string line; std::getline(status, line);)
                if (line.starts_with("SigCgt:") &&
                    (std::stoull(line.substr(7), nullptr, 16) >> (sig - 1) & 1))
                    return true;
            std::this_thread::sleep_for(std::chrono::milliseconds(2));
        }
        return false;
    }

    /// Waits up to `limit` for the exit; returns the exit code, or -1 if it did not exit
    /// (then it is killed).
    int wait(std::chrono::duration<double> limit) {
        auto start = Clock::now();
        int status = 0;
        while (Clock::now() - start < limit) {
            if (::waitpid(pid_, &status, WNOHANG) == pid_)
                return WIFEXITED(status) ? WEXITSTATUS(status) : -2;
            std::this_thread::sleep_for(std::chrono::milliseconds(10));
        }
        ::kill(pid_, SIGKILL);
        ::waitpid(pid_, &status, 0);
        return -1;
    }

    std::string stderrText() const {
        std::ifstream in(err_);
        std::stringstream ss;
        ss << in.rdbuf();
        return ss.str();
    }

  private:
    std::string err_;
    pid_t pid_ = -1;
};

/// A render of the demo scene that takes tens of seconds: it is always still running when
/// the signal comes.
std::vector<std::string> longRender(const std::string& out) {
    return {"--size", "1600x900", "--spp", "64", "-o", out};
}

bool noTemporaries(const std::string& dir) {
    for (const auto& e : fs::directory_iterator(dir))
        if (e.path().filename().string().find(".glint-tmp-") != std::string::npos) return false;
    return true;
}

void expectStopsAndWritesPartial(int sig, int expectedExit) {
    std::string dir = freshDir("interrupt" + std::to_string(sig));
    std::string out = dir + "/out.png";
    Running glint(longRender(out), dir);
    ASSERT_TRUE(glint.waitForHandler(sig));
    std::this_thread::sleep_for(std::chrono::milliseconds(700));
    auto sent = Clock::now();
    glint.signal(sig);
    int code = glint.wait(std::chrono::seconds(10));
    double seconds = std::chrono::duration<double>(Clock::now() - sent).count();

    EXPECT_EQ(code, expectedExit) << glint.stderrText();
    EXPECT_LT(seconds, 3.0) << "did not stop promptly";
    EXPECT_NE(glint.stderrText().find("partial image"), std::string::npos) << glint.stderrText();
    // The finished part was written: a complete, readable PNG of the full size.
    Image8 img = readImage8(out, 3);
    EXPECT_EQ(img.width, 1600);
    EXPECT_EQ(img.height, 900);
    EXPECT_TRUE(noTemporaries(dir));
}

TEST(Interrupt, SigintStopsPromptlyWritesThePartialImageAndExits130) {
    expectStopsAndWritesPartial(SIGINT, 130);
}

TEST(Interrupt, SigtermStopsPromptlyWritesThePartialImageAndExits143) {
    expectStopsAndWritesPartial(SIGTERM, 143);
}

TEST(Interrupt, ASecondSigintLeavesAtOnceAndNeverLeavesABrokenFile) {
    // A scene that takes a good while to load (about 30 MB); the first SIGINT only asks to
    // stop, which loading does not look at, so only the second can end it this early.
    std::string dir = freshDir("interrupt-twice");
    std::string scene = dir + "/big.test";
    {
        std::ofstream s(scene);
        s << "size 64 48\ncamera 0 0 5 0 0 0 0 1 0 45\n";
        for (int i = 0; i < 1500000; ++i) s << "vertex " << i % 97 << " " << i % 89 << ".5 1\n";
        for (int i = 0; i + 2 < 1500000; i += 3)
            s << "tri " << i << " " << i + 1 << " " << i + 2 << "\n";
    }
    std::string out = dir + "/out.png";
    writeFile(out, "previous image");
    Running glint({scene, "-o", out}, dir);
    ASSERT_TRUE(glint.waitForHandler(SIGINT));
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    glint.signal(SIGINT);
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    auto second = Clock::now();
    glint.signal(SIGINT);
    int code = glint.wait(std::chrono::seconds(10));
    double seconds = std::chrono::duration<double>(Clock::now() - second).count();
    EXPECT_EQ(code, 130) << glint.stderrText();
    EXPECT_LT(seconds, 0.25) << "the second signal did not end glint at once";
    EXPECT_EQ(glint.stderrText().find("before rendering"), std::string::npos)
        << "glint finished loading before the second signal: the scene is too small for this "
           "test";
    std::ifstream in(out);
    std::string content((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_EQ(content, "previous image");
    EXPECT_TRUE(noTemporaries(dir));
}

TEST(Interrupt, AnInterruptedPieceWritesNothing) {
    // A piece is whole or absent: glint merge would refuse a partial one.
    std::string dir = freshDir("interrupt-piece");
    std::vector<std::string> args = longRender(dir + "/piece.exr");
    args.insert(args.end(), {"--part", "0/2"});
    Running glint(args, dir);
    ASSERT_TRUE(glint.waitForHandler(SIGINT));
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
    glint.signal(SIGINT);
    EXPECT_EQ(glint.wait(std::chrono::seconds(10)), 130) << glint.stderrText();
    EXPECT_NE(glint.stderrText().find("stopped early; no piece written"), std::string::npos)
        << glint.stderrText();
    EXPECT_FALSE(fs::exists(dir + "/piece.exr"));
    EXPECT_TRUE(noTemporaries(dir));
}

}  // namespace
}  // namespace glint::test
