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
        // mpirun answers SIGINT with SIGTERM to the ranks this many seconds later (1 unless
        // set), and SIGKILL as many after that: on a loaded machine a rank may need more than
        // a second to say why it stopped.
        std::vector<std::string> all = {MPIEXEC,
                                        "--allow-run-as-root",
                                        "--oversubscribe",
                                        "--mca",
                                        "pml",
                                        "ob1",
                                        "--mca",
                                        "btl",
                                        "self,vader",
                                        "--mca",
                                        "odls_base_sigkill_timeout",
                                        "3"};
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
    // Pieces are glint's: glint-mpi would render the whole frame into the piece's file.
    for (const char* piece : {"--part 0/2", "--crop 0,8,0,8", "--samples 0:1"}) {
        r = runMpi("-np 2 " + kGlintMpi + " " + piece + " -o p.exr", dir);
        EXPECT_EQ(r.exitCode, 2) << piece << "\n" << r.err;
        EXPECT_TRUE(contains(r.err, "glint-mpi renders whole frames")) << piece << "\n" << r.err;
    }
    EXPECT_FALSE(fs::exists(dir + "/p.exr"));
}

// Sequences (issue 24): tests/data/gltf/animated.gltf, 99 frames at 24 fps of two boxes
// moving, framed by Glint for the whole animation, tiny.
const std::string kAnimated = "'" + kData + "/gltf/animated.gltf'";
const std::string kTiny = " --size 32x24 --spp 2 -t 1";

/// How many of frames `first` to `last` are the same bytes in files `a` and `b` (patterns
/// with %04d) in `dir`; every file must exist.
int sameFrames(const std::string& dir, const std::string& a, const std::string& b, int first,
               int last) {
    int same = 0;
    for (int n = first; n <= last; ++n) {
        char x[64], y[64];
        std::snprintf(x, sizeof x, a.c_str(), n);
        std::snprintf(y, sizeof y, b.c_str(), n);
        std::string bytes = readBytes(dir + "/" + x);
        EXPECT_FALSE(bytes.empty()) << x;
        same += !bytes.empty() && bytes == readBytes(dir + "/" + y);
    }
    return same;
}

TEST(GlintMpi, AHundredFrameSequenceGivesGlintsFramesByteForByte) {
    std::string dir = freshDir("mpi-frames");
    CommandResult one = runGlint(kAnimated + " --frames 0:99 -q -o g_%04d.png" + kTiny, dir);
    ASSERT_EQ(one.exitCode, 0) << one.err;
    // One job of three ranks renders every frame, rank 0 writing each file.
    CommandResult mpi = runMpi(
        "-np 3 " + kGlintMpi + " " + kAnimated + " --frames 0:99 -o m_%04d.png" + kTiny, dir);
    ASSERT_EQ(mpi.exitCode, 0) << mpi.err;
    EXPECT_TRUE(contains(mpi.err, "glint-mpi: frame 0 (1 of 100)\n")) << mpi.err;
    EXPECT_TRUE(contains(mpi.err, "glint-mpi: frame 99 (100 of 100)\n")) << mpi.err;
    EXPECT_TRUE(contains(mpi.err, "glint-mpi: wrote m_0099.png (32x24, 3 ranks)")) << mpi.err;
    EXPECT_EQ(sameFrames(dir, "g_%04d.png", "m_%04d.png", 0, 99), 100);
    // The frames are frames of an animation: no two neighbours alike.
    EXPECT_NE(readBytes(dir + "/g_0041.png"), readBytes(dir + "/g_0042.png"));
}

TEST(GlintMpi, FrameTimeAtAndAStepPoseTheFramesGlintDoes) {
    std::string dir = freshDir("mpi-frame");
    const std::string mpi = "-np 2 " + kGlintMpi + " " + kAnimated + " -q";
    ASSERT_EQ(runGlint(kAnimated + " --frame 42 -q -o g.png" + kTiny, dir).exitCode, 0);
    CommandResult r = runMpi(mpi + " --frame 42 -o frame.png" + kTiny, dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    // Frame 42 at 24 fps is 1.75 s; at 12 fps, frame 21.
    r = runMpi(mpi + " --time-at 1.75 -o time.png" + kTiny, dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    r = runMpi(mpi + " --frames 19:23:2 --fps 12 -o s_####.png" + kTiny, dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const std::string g = readBytes(dir + "/g.png");
    ASSERT_FALSE(g.empty());
    EXPECT_TRUE(readBytes(dir + "/frame.png") == g);
    EXPECT_TRUE(readBytes(dir + "/time.png") == g);
    EXPECT_TRUE(readBytes(dir + "/s_0021.png") == g);
    EXPECT_TRUE(fs::exists(dir + "/s_0019.png") && fs::exists(dir + "/s_0023.png"));
    EXPECT_FALSE(fs::exists(dir + "/s_0020.png"));
    EXPECT_NE(readBytes(dir + "/s_0019.png"), g);
}

TEST(GlintMpi, TimingsOfASequenceGoToAFilePerFrameEachOfItsOwnLoad) {
    std::string dir = freshDir("mpi-frame-timings");
    CommandResult r = runMpi("-np 3 " + kGlintMpi + " " + kAnimated +
                                 " --frames 4:5 -q -o f%d.png --timings t%d.json" + kTiny,
                             dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    for (const char* name : {"/t4.json", "/t5.json"}) {
        std::string json = readBytes(dir + name);
        EXPECT_TRUE(contains(json, "\"ranks\": 3,")) << name << json;
        // Each frame's own load: one entry per rank, not the sequence's so far.
        EXPECT_TRUE(contains(json, "\"threads\": [1, 1, 1],")) << name << json;
    }
}

TEST(GlintMpi, SequenceUsageErrorsAreGlintsAndPrintedOnce) {
    std::string dir = freshDir("mpi-frames-usage");
    struct Case {
        const char* args;
        int code;
        const char* message;
    } cases[] = {
        {"--frames 0:3 -o out.png", 2,
         "glint: error: --frames 0:3 writes a file per frame: -o needs a frame number in its "
         "name, as out_%04d.png or out_####.png, got 'out.png'"},
        {"--frames 3:1", 2, "the last frame comes before the first in '3:1'"},
        {"--frames 1:3:0", 2, "the step must be at least 1"},
        {"--frame 1 --frames 1:2", 2, "excludes"},
        {"--animation Walk --frames 0:1 -o w%d.png", 1,
         "no animation is named 'Walk': the file has 1 animation: 0 = 'Turn'"},
    };
    for (const Case& c : cases) {
        CommandResult r =
            runMpi("-np 3 " + kGlintMpi + " " + kAnimated + " " + c.args + kTiny + " -q", dir);
        EXPECT_EQ(r.exitCode, c.code) << c.args << "\n" << r.err;
        size_t first = r.err.find(c.message);
        ASSERT_NE(first, std::string::npos) << c.args << "\n" << r.err;
        EXPECT_EQ(r.err.find(c.message, first + 1), std::string::npos) << c.args << "\n" << r.err;
    }
    EXPECT_EQ(leftovers(dir), "");
}

TEST(GlintMpi, SigintMidSequenceKeepsTheFramesWrittenAndStopsEveryRank) {
    std::string dir = freshDir("mpi-frames-sigint");
    // Frames of a second or so each on three ranks of one thread.
    Background job({"-np", "3", GLINT_MPI_BINARY, kData + "/gltf/animated.gltf", "--frames", "0:9",
                    "--size", "160x120", "--spp", "256", "-t", "1", "-o", "f_%04d.png"},
                   dir);
    auto start = std::chrono::steady_clock::now();
    while (!fs::exists(dir + "/f_0000.png") &&
           std::chrono::steady_clock::now() - start < std::chrono::seconds(40))
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    ASSERT_TRUE(fs::exists(dir + "/f_0000.png")) << readBytes(dir + "/.stderr");
    ::kill(job.pid(), SIGINT);
    int code = job.wait(std::chrono::seconds(30));
    std::string err = readBytes(dir + "/.stderr");
    EXPECT_NE(code, 0) << err;
    EXPECT_NE(code, -1) << "the job did not end: " << err;
    EXPECT_TRUE(contains(err, "glint-mpi: SIGTERM: stopped")) << err;
    EXPECT_FALSE(fs::exists(dir + "/f_0009.png"));
    // Whole frames only: no temporary file, no partial image.
    for (const auto& e : fs::directory_iterator(dir)) {
        std::string name = e.path().filename().string();
        if (name == ".stdout" || name == ".stderr") continue;
        EXPECT_EQ(name.size(), std::string("f_0000.png").size()) << name;
        EXPECT_EQ(name.rfind("f_", 0), 0u) << name;
    }
}

}  // namespace
}  // namespace glint::test
