// glint-mpi under mpirun on this machine (issue 13): three ranks give glint's image byte for
// byte; a rank that cannot load the scene, loads another one, or dies mid-render ends the job
// with a message naming it and no image. Every command runs under `timeout`: no test can hang.
// mpirun runs as root if need be, with more ranks than cores, over shared memory only.

#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include "cli/cli_support.h"

extern char** environ;

namespace glint::test {
namespace {

namespace fs = std::filesystem;

const std::string kData = GLINT_TEST_DATA_DIR;

/// `mpirun <args>` in `dir`, given up after 60 s (the job is then killed: exit 124).
CommandResult runMpi(const std::string& args, const std::string& dir) {
    fs::create_directories(dir);
    std::string cmd = "cd '" + dir +
                      "' && timeout -k 5 60 '" MPIEXEC
                      "' --allow-run-as-root --oversubscribe --mca pml ob1 --mca btl self,vader " +
                      args + " >.stdout 2>.stderr </dev/null";
    int status = std::system(cmd.c_str());
    CommandResult r;
    r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.out = readBytes(dir + "/.stdout");
    r.err = readBytes(dir + "/.stderr");
    return r;
}

const std::string kGlintMpi = std::string("'") + GLINT_MPI_BINARY + "'";

/// Files in `dir` other than the captured output: what a failed job must not leave.
std::string leftovers(const std::string& dir) {
    std::string s;
    for (const auto& e : fs::directory_iterator(dir)) {
        std::string name = e.path().filename().string();
        if (name != ".stdout" && name != ".stderr" && !e.is_directory()) s += name + " ";
    }
    return s;
}

TEST(GlintMpi, ThreeRanksGiveTheSingleProcessBytesForAWhittedCourseScene) {
    std::string dir = freshDir("mpi-whitted");
    std::string scene = "'" + kData + "/cse167x/scene6.test'";
    CommandResult one = runGlint(scene + " -q -o one.png", dir);
    ASSERT_EQ(one.exitCode, 0) << one.err;
    // Two threads on each rank: tiles from rank 0's own threads and from the others'.
    CommandResult mpi = runMpi("-np 3 " + kGlintMpi + " " + scene + " -t 2 -o mpi.png", dir);
    ASSERT_EQ(mpi.exitCode, 0) << mpi.err;
    EXPECT_TRUE(contains(mpi.err, "glint-mpi: wrote mpi.png (640x480, 3 ranks)")) << mpi.err;
    std::string a = readBytes(dir + "/one.png"), b = readBytes(dir + "/mpi.png");
    ASSERT_FALSE(a.empty());
    EXPECT_TRUE(a == b) << "the PNG files differ";
}

TEST(GlintMpi, ThreeRanksGiveTheSingleProcessBytesForAPathTracedScene) {
    std::string dir = freshDir("mpi-path");
    // The Cornell box, path traced at 256 samples per pixel (every sample draws random
    // numbers), on an image whose sides are no multiple of the 32-pixel tiles, to a float
    // file (PFM), whose bytes show every pixel's value to float precision.
    const std::string scene = std::string("'" GLINT_SCENES_DIR "/cornell.test'") +
                              " --integrator path --size 70x45 --spp 256 --seed 7";
    CommandResult one = runGlint(scene + " -q -o one.pfm", dir);
    ASSERT_EQ(one.exitCode, 0) << one.err;
    CommandResult mpi = runMpi("-np 3 " + kGlintMpi + " " + scene + " -q -t 1 -o mpi.pfm", dir);
    ASSERT_EQ(mpi.exitCode, 0) << mpi.err;
    EXPECT_EQ(mpi.err, "");  // -q: nothing but errors
    std::string a = readBytes(dir + "/one.pfm"), b = readBytes(dir + "/mpi.pfm");
    ASSERT_GT(a.size(), 70u * 45 * 12);
    EXPECT_TRUE(a == b) << "the PFM files differ";
}

TEST(GlintMpi, AdaptiveSamplingPassesAndTheDenoiserGiveTheSingleProcessBytes) {
    std::string dir = freshDir("mpi-clean");
    const std::string scene = std::string("'" GLINT_SCENES_DIR "/cornell.test'") +
                              " --integrator path --size 70x45 --spp 64 --noise-threshold 0.05 "
                              "--min-spp 4 --aov all --denoise";
    CommandResult one = runGlint(scene + " -q -o one.exr", dir);
    ASSERT_EQ(one.exitCode, 0) << one.err;
    CommandResult mpi = runMpi("-np 3 " + kGlintMpi + " " + scene + " -t 1 -o mpi.exr", dir);
    ASSERT_EQ(mpi.exitCode, 0) << mpi.err;
    EXPECT_TRUE(contains(mpi.err, "glint-mpi: denoised in ")) << mpi.err;
    std::string a = readBytes(dir + "/one.exr"), b = readBytes(dir + "/mpi.exr");
    ASSERT_GT(a.size(), 1000u);
    EXPECT_TRUE(a == b) << "the EXR files differ";
}

/// A scene with a mesh, in `dir`: `mesh` names the OBJ file, `obj` its text (none if empty).
void writeMeshScene(const std::string& dir, const std::string& obj) {
    writeFile(dir + "/s.test",
              "size 40 30\ncamera 0 0 4  0 0 0  0 1 0  45\npoint 1 1 3 1 1 1\n"
              "diffuse 0.8 0.2 0.2\nmesh m.obj\n");
    if (!obj.empty()) writeFile(dir + "/m.obj", obj);
}

const std::string kTriangle = "v -1 -1 0\nv 1 -1 0\nv 0 1 0\nf 1 2 3\n";

// Per-rank working directories (mpirun's MPMD form, `-np 1 --wdir A prog : -np 2 --wdir B
// prog`) give rank 0 a view of the files that the others do not share: a test-only stand-in
// for a node whose filesystem is missing or holds other files.
std::string mpmd(const std::string& rootDir, const std::string& otherDir, const std::string& args) {
    return "-np 1 --wdir '" + rootDir + "' " + kGlintMpi + " " + args + " : -np 2 --wdir '" +
           otherDir + "' " + kGlintMpi + " " + args;
}

TEST(GlintMpi, RanksThatCannotReadAMeshEndTheJobNamingThem) {
    std::string dir = freshDir("mpi-missing"), a = dir + "/a", b = dir + "/b";
    writeMeshScene(a, kTriangle);
    writeMeshScene(b, "");  // ranks 1 and 2 see the scene but not its mesh
    CommandResult r = runMpi(mpmd(a, b, "s.test -o out.png"), dir);
    EXPECT_EQ(r.exitCode, 1) << r.err;
    EXPECT_TRUE(contains(r.err, "glint-mpi: ranks 1, 2 failed to load the scene:")) << r.err;
    EXPECT_TRUE(contains(r.err, "m.obj")) << r.err;
    EXPECT_FALSE(contains(r.err, "rank 0")) << r.err;
    EXPECT_TRUE(contains(r.err, "nothing rendered")) << r.err;
    EXPECT_EQ(leftovers(a) + leftovers(b), "m.obj s.test s.test ");
}

TEST(GlintMpi, ARankWithAParseErrorEndsTheJobWithItsMessage) {
    std::string dir = freshDir("mpi-parse"), a = dir + "/a", b = dir + "/b";
    writeMeshScene(a, kTriangle);
    writeMeshScene(b, kTriangle);
    writeFile(b + "/s.test", "size 40 30\ncamera 0 0 4 0 0 0 0 1 0\n");  // 9 numbers, not 10
    CommandResult r = runMpi(mpmd(a, b, "s.test -o out.png"), dir);
    EXPECT_EQ(r.exitCode, 1) << r.err;
    EXPECT_TRUE(contains(r.err, "ranks 1, 2 failed to load the scene:")) << r.err;
    EXPECT_TRUE(contains(r.err, "s.test:2:")) << r.err;
    EXPECT_FALSE(fs::exists(a + "/out.png"));
}

TEST(GlintMpi, RanksHoldingADifferentMeshEndTheJobBeforeRendering) {
    std::string dir = freshDir("mpi-hash"), a = dir + "/a", b = dir + "/b";
    writeMeshScene(a, kTriangle);
    writeMeshScene(b, "v -1 -1 0\nv 1 -1 0\nv 0 2 0\nf 1 2 3\n");  // one vertex moved
    CommandResult r = runMpi(mpmd(a, b, "s.test -o out.png"), dir);
    EXPECT_EQ(r.exitCode, 1) << r.err;
    EXPECT_TRUE(contains(r.err,
                         "glint-mpi: ranks 1, 2 loaded a different scene than rank 0: "
                         "input hash "))
        << r.err;
    EXPECT_FALSE(fs::exists(a + "/out.png"));
    // The same files in both places: the job renders.
    writeMeshScene(b, kTriangle);
    r = runMpi(mpmd(a, b, "s.test -q -o out.png"), dir);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(fs::exists(a + "/out.png"));
}

/// mpirun running in the background in `dir`, its output going to .stdout and .stderr there.
class Background {
  public:
    Background(const std::vector<std::string>& args, const std::string& dir) {
        std::vector<std::string> all = {
            MPIEXEC, "--allow-run-as-root", "--oversubscribe", "--mca", "pml", "ob1", "--mca",
            "btl",   "self,vader"};
        all.insert(all.end(), args.begin(), args.end());
        std::vector<char*> argv;
        for (auto& a : all) argv.push_back(a.data());
        argv.push_back(nullptr);
        posix_spawn_file_actions_t actions;
        posix_spawn_file_actions_init(&actions);
        posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
        std::string out = dir + "/.stdout", err = dir + "/.stderr";
        posix_spawn_file_actions_addopen(&actions, 1, out.c_str(), O_WRONLY | O_CREAT, 0644);
        posix_spawn_file_actions_addopen(&actions, 2, err.c_str(), O_WRONLY | O_CREAT, 0644);
        std::string cwd = fs::current_path().string();
        fs::current_path(dir);  // mpirun's ranks start in its working directory
        EXPECT_EQ(posix_spawn(&pid_, all[0].c_str(), &actions, nullptr, argv.data(), environ), 0);
        fs::current_path(cwd);
        posix_spawn_file_actions_destroy(&actions);
    }

    pid_t pid() const { return pid_; }

    /// Waits up to `limit` for mpirun's exit; returns its exit code, 128 + the signal that
    /// ended it, or -1 if it did not end (it is then killed).
    int wait(std::chrono::seconds limit) {
        auto start = std::chrono::steady_clock::now();
        int status = 0;
        while (std::chrono::steady_clock::now() - start < limit) {
            if (::waitpid(pid_, &status, WNOHANG) == pid_)
                return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
            std::this_thread::sleep_for(std::chrono::milliseconds(20));
        }
        ::kill(pid_, SIGKILL);
        ::waitpid(pid_, &status, 0);
        return -1;
    }

  private:
    pid_t pid_ = -1;
};

/// The process of glint-mpi's rank `rank` working in `dir` (as /proc shows it), waiting up to
/// 20 s for it to start; -1 if none.
pid_t findRank(int rank, const std::string& dir) {
    const std::string mark = "OMPI_COMM_WORLD_RANK=" + std::to_string(rank);
    auto start = std::chrono::steady_clock::now();
    while (std::chrono::steady_clock::now() - start < std::chrono::seconds(20)) {
        for (const auto& e : fs::directory_iterator("/proc")) {
            std::string name = e.path().filename().string();
            if (name.find_first_not_of("0123456789") != std::string::npos) continue;
            if (readBytes(e.path().string() + "/comm") != "glint-mpi\n") continue;
            std::error_code ec;
            if (fs::read_symlink(e.path() / "cwd", ec) != fs::path(dir)) continue;
            std::string env = readBytes(e.path().string() + "/environ");
            if (env.find(mark + '\0') != std::string::npos) return std::stoi(name);
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    return -1;
}

/// Several seconds of path tracing on three ranks: what the next tests stop half-way.
std::vector<std::string> longRender() {
    return {"-np",
            "3",
            GLINT_MPI_BINARY,
            std::string(GLINT_SCENES_DIR) + "/cornell.test",
            "--integrator",
            "path",
            "--size",
            "200x150",
            "--spp",
            "1024",
            "-t",
            "1",
            "-o",
            "out.png"};
}

TEST(GlintMpi, ARankThatCrashesMidRenderEndsTheJobNamingItAndLeavesNoImage) {
    std::string dir = freshDir("mpi-crash");
    Background job(longRender(), dir);
    pid_t rank2 = findRank(2, dir);
    ASSERT_GT(rank2, 0) << readBytes(dir + "/.stderr");
    std::this_thread::sleep_for(std::chrono::milliseconds(800));  // into the render
    ::kill(rank2, SIGSEGV);
    int code = job.wait(std::chrono::seconds(30));
    std::string err = readBytes(dir + "/.stderr");
    EXPECT_NE(code, 0) << err;
    EXPECT_NE(code, -1) << "the job did not end: " << err;
    // mpirun's own message names the rank.
    EXPECT_TRUE(contains(err, "process rank 2 with PID")) << err;
    EXPECT_TRUE(contains(err, "Segmentation fault")) << err;
    EXPECT_EQ(leftovers(dir), "");
}

TEST(GlintMpi, SigintToMpirunStopsEveryRankAndLeavesNoImage) {
    std::string dir = freshDir("mpi-sigint");
    Background job(longRender(), dir);
    ASSERT_GT(findRank(2, dir), 0) << readBytes(dir + "/.stderr");
    std::this_thread::sleep_for(std::chrono::milliseconds(800));
    ::kill(job.pid(), SIGINT);
    int code = job.wait(std::chrono::seconds(30));
    std::string err = readBytes(dir + "/.stderr");
    EXPECT_NE(code, 0) << err;
    EXPECT_NE(code, -1) << "the job did not end: " << err;
    // mpirun passes SIGTERM on to the ranks; rank 0 says what happened.
    EXPECT_TRUE(contains(err, "glint-mpi: SIGTERM: stopped; no image written")) << err;
    EXPECT_EQ(leftovers(dir), "");
}

TEST(GlintMpi, UsageErrorsArePrintedOnceAndExit2) {
    std::string dir = freshDir("mpi-usage");
    CommandResult r = runMpi("-np 3 " + kGlintMpi + " --spp 0", dir);
    EXPECT_EQ(r.exitCode, 2) << r.err;
    size_t first = r.err.find("glint-mpi: error: --spp");
    ASSERT_NE(first, std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("glint-mpi: error: --spp", first + 1), std::string::npos) << r.err;
    r = runMpi("-np 2 " + kGlintMpi + " --time 5", dir);
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_TRUE(contains(r.err, "--time is not available in glint-mpi")) << r.err;
}

}  // namespace
}  // namespace glint::test
