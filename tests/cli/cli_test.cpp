// The CLI as users meet it: exit codes (0 ok, 1 scene or render error, 2 usage error), where
// the image goes and in which format, the options that change the render, and what is printed.
// Scene diagnostics (file:line:col errors and warnings) are in scene_errors_test.cpp.

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <vector>

#include "cli/cli_support.h"
#include "glint/io/image/image_io.h"

namespace glint::test {
namespace {

namespace fs = std::filesystem;

/// A small, valid scene: 2 triangles, 2 spheres (one a mirror), 2 lights, no output line.
const char* const kScene =
    "size 64 48\n"
    "camera 0 1 6 0 0 0 0 1 0 45\n"
    "maxdepth 3\n"
    "point 3 4 5 0.8 0.8 0.8\n"
    "directional 0 1 1 0.3 0.3 0.3\n"
    "ambient 0.1 0.1 0.1\n"
    "diffuse 0.5 0.5 0.5\n"
    "specular 0.3 0.3 0.3\n"
    "shininess 20\n"
    "vertex -3 -1 -3\n"
    "vertex 3 -1 -3\n"
    "vertex 3 -1 3\n"
    "vertex -3 -1 3\n"
    "tri 0 2 1\n"
    "tri 0 3 2\n"
    "sphere -1 0 0 1\n"
    "specular 0.9 0.9 0.9\n"
    "sphere 1.2 0 -0.5 0.8\n";

/// Regular files in `dir` other than the harness's own, sorted.
std::vector<std::string> filesIn(const std::string& dir) {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir))
        if (e.is_regular_file()) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
}

std::vector<std::string> lines(const std::string& text) {
    std::vector<std::string> out;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) out.push_back(line);
    return out;
}

/// A directory holding kScene as scene.test.
std::string sceneDir(const std::string& name) {
    std::string dir = freshDir(name);
    writeFile(dir + "/scene.test", kScene);
    return dir;
}

// ---- The built-in demo and output formats ----

TEST(Cli, BuiltInDemoSceneRendersToGlintPng) {
    std::string dir = freshDir("demo");
    CommandResult r = runGlint("-q --size 160x90", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(filesIn(dir), std::vector<std::string>{"glint.png"});
    Image8 img = readImage8(dir + "/glint.png", 3);
    EXPECT_EQ(img.width, 160);
    EXPECT_EQ(img.height, 90);
    // The top row is the demo's sky: bluer than it is red.
    EXPECT_GT(img.at(0, 0, 2), img.at(0, 0, 0));
}

TEST(Cli, OutputWithPngExtensionWritesAPng) {
    std::string dir = sceneDir("png");
    CommandResult r = runGlint("-q scene.test -o out.png", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(readBytes(dir + "/out.png").substr(0, 8), "\x89PNG\r\n\x1a\n");
    Image8 img = readImage8(dir + "/out.png", 3);
    EXPECT_EQ(img.width, 64);
    EXPECT_EQ(img.height, 48);
}

TEST(Cli, OutputWithPpmExtensionWritesBinaryP6) {
    std::string dir = sceneDir("ppm");
    CommandResult r = runGlint("-q scene.test -o out.ppm", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    std::string bytes = readBytes(dir + "/out.ppm");
    const std::string header = "P6\n64 48\n255\n";
    EXPECT_EQ(bytes.substr(0, header.size()), header);
    EXPECT_EQ(bytes.size(), header.size() + 64 * 48 * 3);
}

TEST(Cli, OutputWithPfmExtensionWritesFloatPf) {
    std::string dir = sceneDir("pfm");
    CommandResult r = runGlint("-q scene.test -o out.pfm", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    std::string bytes = readBytes(dir + "/out.pfm");
    const std::string header = "PF\n64 48\n-1.0\n";
    EXPECT_EQ(bytes.substr(0, header.size()), header);
    EXPECT_EQ(bytes.size(), header.size() + 64 * 48 * 12);
}

TEST(Cli, OutputExtensionIsCaseInsensitive) {
    std::string dir = sceneDir("upper");
    CommandResult r = runGlint("-q scene.test -o OUT.PPM", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(readBytes(dir + "/OUT.PPM").substr(0, 3), "P6\n");
}

TEST(Cli, UnknownOutputExtensionIsAUsageErrorAndWritesNothing) {
    std::string dir = sceneDir("badext");
    for (const char* out : {"out.jpg", "out", "out.png.bak"}) {
        SCOPED_TRACE(out);
        CommandResult r = runGlint(std::string("scene.test -o ") + out, dir);
        EXPECT_EQ(r.exitCode, 2);
        EXPECT_TRUE(contains(r.err, std::string("glint: error: cannot write '") + out +
                                        "': unknown image format (use .png, .ppm, .pfm or .exr)"))
            << r.err;
    }
    EXPECT_EQ(filesIn(dir), std::vector<std::string>{"scene.test"});
}

// ---- Where the image goes by default ----

TEST(Cli, DefaultOutputIsTheScenesOutputLineInTheCurrentDirectory) {
    std::string dir = freshDir("outline");
    writeFile(dir + "/scenes/lined.test", std::string(kScene) + "output result.ppm\n");
    CommandResult r = runGlint("-q scenes/lined.test", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(readBytes(dir + "/result.ppm").substr(0, 3), "P6\n");
    EXPECT_FALSE(fs::exists(dir + "/scenes/result.ppm"));
    EXPECT_FALSE(fs::exists(dir + "/lined.png"));
}

TEST(Cli, DefaultOutputWithoutOutputLineIsSceneStemPngInTheCurrentDirectory) {
    std::string dir = freshDir("stem");
    writeFile(dir + "/scenes/ball.test", kScene);
    CommandResult r = runGlint("-q scenes/ball.test", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(filesIn(dir), std::vector<std::string>{"ball.png"});
    EXPECT_FALSE(fs::exists(dir + "/scenes/ball.png"));
    EXPECT_EQ(readImage8(dir + "/ball.png").width, 64);
}

TEST(Cli, OutputOptionOverridesTheScenesOutputLine) {
    std::string dir = freshDir("override");
    writeFile(dir + "/s.test", std::string(kScene) + "output fromscene.png\n");
    CommandResult r = runGlint("-q s.test -o fromcli.pfm", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(fs::exists(dir + "/fromcli.pfm"));
    EXPECT_FALSE(fs::exists(dir + "/fromscene.png"));
}

TEST(Cli, OutputLineWithUnknownExtensionWarnsThenFailsUnlessOverridden) {
    std::string dir = freshDir("linejpg");
    writeFile(dir + "/s.test", std::string(kScene) + "output picture.jpg\n");
    const std::string warning =
        "s.test:19:8: warning: Glint cannot write 'picture.jpg': use a .png, .ppm, .pfm or .exr "
        "name here or choose one with -o";

    CommandResult r = runGlint("-q s.test", dir);
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_TRUE(contains(r.err, warning)) << r.err;
    EXPECT_TRUE(contains(r.err, "glint: error: cannot write 'picture.jpg'")) << r.err;
    EXPECT_EQ(filesIn(dir), std::vector<std::string>{"s.test"});

    r = runGlint("-q s.test -o picture.png", dir);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(fs::exists(dir + "/picture.png"));
}

// ---- Options that change the render ----

TEST(Cli, SizeOptionSetsTheImageDimensions) {
    std::string dir = sceneDir("size");
    CommandResult r = runGlint("-q scene.test --size 37x21 -o out.png", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    Image8 img = readImage8(dir + "/out.png", 3);
    EXPECT_EQ(img.width, 37);
    EXPECT_EQ(img.height, 21);
}

TEST(Cli, SizeOptionRejectsMalformedOrHugeValues) {
    std::string dir = sceneDir("badsize");
    struct Case {
        const char* size;
        const char* message;
    };
    const char* form = "--size expects WIDTHxHEIGHT";
    const char* side = "each side must be 1 to 32768";
    for (Case c : {Case{"abc", form},
                   {"10x", form},
                   {"x10", form},
                   {"64x48x", form},
                   {"64*48", form},
                   {" 64x48", form},
                   {"64x 48", form},
                   {"99999999999999999999x1", form},
                   {"0x10", side},
                   {"10x0", side},
                   {"-5x5", side},
                   {"20000x20000", "at most 134217728 pixels"}}) {
        SCOPED_TRACE(c.size);
        CommandResult r = runGlint(std::string("scene.test --size '") + c.size + "'", dir);
        EXPECT_EQ(r.exitCode, 2);
        EXPECT_TRUE(contains(r.err, c.message)) << r.err;
    }
    EXPECT_EQ(filesIn(dir), std::vector<std::string>{"scene.test"});
}

TEST(Cli, SizeOptionErrorStatesTheSideLimitWhenASideIsTooLong) {
    // 40000x10 is only 400,000 pixels: the message must name the limit it breaks, the
    // largest side (32768, as the loader's `size` error does), not only the pixel budget.
    std::string dir = sceneDir("sidelimit");
    CommandResult r = runGlint("scene.test --size 40000x10", dir);
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_TRUE(contains(r.err, "32768")) << r.err;
}

TEST(Cli, MaxDepthOptionOverridesTheScene) {
    std::string dir = freshDir("maxdepth");
    CommandResult check = runGlint("--check --maxdepth 0", dir);
    EXPECT_EQ(check.exitCode, 0) << check.err;
    EXPECT_TRUE(contains(check.out, "maxdepth 0,")) << check.out;

    // The demo has a mirror sphere: without reflections no reflection ray is traced and the
    // image changes.
    CommandResult r0 = runGlint("-q --stats --size 64x48 --maxdepth 0 -o d0.ppm", dir);
    CommandResult r5 = runGlint("-q --stats --size 64x48 -o d5.ppm", dir);
    ASSERT_EQ(r0.exitCode, 0) << r0.err;
    ASSERT_EQ(r5.exitCode, 0) << r5.err;
    EXPECT_TRUE(contains(r0.out, " 0 reflection,")) << r0.out;
    EXPECT_FALSE(contains(r5.out, " 0 reflection,")) << r5.out;
    EXPECT_NE(readBytes(dir + "/d0.ppm"), readBytes(dir + "/d5.ppm"));

    check = runGlint("--check --maxdepth 64", dir);
    EXPECT_EQ(check.exitCode, 0) << check.err;
    EXPECT_TRUE(contains(check.out, "maxdepth 64,")) << check.out;
}

TEST(Cli, MaxDepthOptionRejectsOutOfRangeOrNonIntegerValues) {
    std::string dir = freshDir("badmaxdepth");
    for (const char* depth : {"-1", "65", "abc", "1.5", "''"}) {
        SCOPED_TRACE(depth);
        CommandResult r = runGlint(std::string("--check --maxdepth ") + depth, dir);
        EXPECT_EQ(r.exitCode, 2);
        EXPECT_TRUE(contains(r.err, "--maxdepth")) << r.err;
        EXPECT_TRUE(r.out.empty()) << r.out;
    }
}

TEST(Cli, MaxBouncesSetsLimitsByKindOverTheModelModesOwn) {
    std::string dir = freshDir("maxbounces");
    const std::string slabs = std::string(GLINT_SOURCE_DIR) + "/tests/data/gltf/glass-slabs.gltf";
    CommandResult r = runGlint(slabs + " --check", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(contains(r.out, "maxdepth 12 (diffuse 8, glossy 8, transmission 12, volume 8),"))
        << r.out;
    r = runGlint(slabs + " --check --max-bounces total=20,diffuse=3,volume=64", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(contains(r.out, "maxdepth 20 (diffuse 3, glossy 8, transmission 12, volume 64),"))
        << r.out;
    r = runGlint("--check --max-bounces 7", dir);  // a scene: the total alone, as --maxdepth
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(contains(r.out, "maxdepth 7,")) << r.out;

    for (const char* bad : {"0", "65", "diffuse=0", "glass=4", "total=4,", "diffuse", "4,5"}) {
        SCOPED_TRACE(bad);
        r = runGlint(std::string("--check --max-bounces ") + bad, dir);
        EXPECT_EQ(r.exitCode, 2);
        EXPECT_TRUE(contains(r.err, "--max-bounces")) << r.err;
        EXPECT_TRUE(r.out.empty()) << r.out;
    }
    r = runGlint("--check --max-bounces glass=4", dir);
    EXPECT_TRUE(contains(r.err, "total, diffuse, glossy, transmission or volume")) << r.err;
}

TEST(Cli, IntegratorOptionOverridesTheScenesAndNamesTheChoicesWhenWrong) {
    std::string dir = sceneDir("integrator");
    writeFile(dir + "/named.test", std::string("integrator whitted\n") + kScene);
    ASSERT_EQ(runGlint("-q scene.test -o default.pfm", dir).exitCode, 0);
    ASSERT_EQ(runGlint("-q scene.test --integrator whitted -o option.pfm", dir).exitCode, 0);
    ASSERT_EQ(runGlint("-q named.test -o named.pfm", dir).exitCode, 0);
    EXPECT_EQ(readBytes(dir + "/default.pfm"), readBytes(dir + "/option.pfm"));
    EXPECT_EQ(readBytes(dir + "/default.pfm"), readBytes(dir + "/named.pfm"));

    CommandResult r = runGlint("scene.test --integrator raymarch", dir);
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_TRUE(contains(r.err, "--integrator")) << r.err;
    EXPECT_TRUE(contains(r.err, "whitted")) << r.err;
    EXPECT_TRUE(contains(runGlint("--help", dir).out, "--integrator")) << "missing from --help";
}

TEST(Cli, OneAndTwoThreadsGiveByteIdenticalImages) {
    std::string dir = sceneDir("threads");
    for (const char* ext : {".png", ".pfm"}) {
        SCOPED_TRACE(ext);
        std::string one = std::string("t1") + ext, two = std::string("t2") + ext;
        ASSERT_EQ(runGlint("-q scene.test -t 1 -o " + one, dir).exitCode, 0);
        ASSERT_EQ(runGlint("-q scene.test --threads 2 -o " + two, dir).exitCode, 0);
        std::string a = readBytes(dir + "/" + one), b = readBytes(dir + "/" + two);
        EXPECT_GT(a.size(), 100u);
        EXPECT_TRUE(a == b) << "images differ between -t 1 and -t 2";
    }
}

TEST(Cli, EveryKernelChoiceGivesTheSameImage) {
    std::string dir = sceneDir("kernels");
    ASSERT_EQ(runGlint("-q scene.test -o auto.pfm", dir).exitCode, 0);
    ASSERT_EQ(runGlint("-q scene.test --kernels portable -o portable.pfm", dir).exitCode, 0);
    EXPECT_EQ(readBytes(dir + "/auto.pfm"), readBytes(dir + "/portable.pfm"));
    // avx2 works where the CPU has it, and is a usage error elsewhere.
    CommandResult avx2 = runGlint("-q scene.test --kernels avx2 -o avx2.pfm", dir);
    if (avx2.exitCode == 0)
        EXPECT_EQ(readBytes(dir + "/auto.pfm"), readBytes(dir + "/avx2.pfm"));
    else
        EXPECT_EQ(avx2.exitCode, 2) << avx2.err;

    CommandResult r = runGlint("scene.test --kernels sse9", dir);
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_TRUE(contains(r.err, "--kernels")) << r.err;
    EXPECT_TRUE(contains(runGlint("--help", dir).out, "--kernels")) << "missing from --help";
}

TEST(Cli, ZeroOrNonNumericThreadCountIsAUsageError) {
    std::string dir = sceneDir("badthreads");
    for (const char* t : {"0", "-1", "abc"}) {
        SCOPED_TRACE(t);
        CommandResult r = runGlint(std::string("scene.test -t ") + t, dir);
        EXPECT_EQ(r.exitCode, 2);
        EXPECT_TRUE(contains(r.err, "--threads")) << r.err;
    }
    EXPECT_EQ(filesIn(dir), std::vector<std::string>{"scene.test"});
}

// ---- --check, --stats, -q ----

TEST(Cli, CheckPrintsAOneLineSummaryAndWritesNoImage) {
    std::string dir = sceneDir("check");
    CommandResult r = runGlint("--check scene.test", dir);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(r.out,
              "scene.test: ok: 64x48, 2 triangles, 2 spheres, 2 lights, maxdepth 3, output "
              "scene.png\n");
    EXPECT_EQ(r.err, "");
    EXPECT_EQ(filesIn(dir), std::vector<std::string>{"scene.test"});

    // Overrides show in the summary.
    r = runGlint("--check scene.test --size 32x24 -o x.pfm", dir);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(contains(r.out, ": ok: 32x24,")) << r.out;
    EXPECT_TRUE(contains(r.out, "output x.pfm\n")) << r.out;
}

TEST(Cli, CheckCountsTheShapeExtensionsByKind) {
    std::string dir = freshDir("checkshapes");
    writeFile(dir + "/s.test",
              "size 64 48\ncamera 0 0 5 0 0 0 0 1 0 45\nsphere 0 0 0 1\nbox 0 0 0 1 1 1\n"
              "box 2 2 2 3 3 3\ncylinder 0 0 0 0 1 0 1\ncone 0 0 0 1 0 1 0 0\n"
              "disk 0 0 0 0 0 1 1\nplane 0 -1 0 0 1 0\nvertex 0 0 0\nvertex 1 0 0\n"
              "vertex 1 1 0\nvertex 0 1 0\npolygon 0 1 2 3\n");
    CommandResult r = runGlint("--check s.test", dir);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(r.out,
              "s.test: ok: 64x48, 2 triangles, 1 sphere, 2 boxes, 1 cylinder, 1 cone, 1 disk, "
              "1 plane, 0 lights, maxdepth 5, output s.png\n");
}

TEST(Cli, CheckExitsOneOnABadScene) {
    std::string dir = freshDir("checkbad");
    writeFile(dir + "/bad.test", "size 64 48\ncamera 0 0 5 0 0 0 0 1 0 45\nsphere 0 0 0\n");
    CommandResult r = runGlint("--check bad.test", dir);
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_EQ(r.out, "");
    EXPECT_TRUE(contains(r.err, "bad.test:3:1: error:")) << r.err;
}

TEST(Cli, StatsPrintsPhaseTimesRaysAndThroughput) {
    std::string dir = sceneDir("stats");
    CommandResult r = runGlint("-q --stats scene.test", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const std::string num = "[0-9]+\\.[0-9]+";
    EXPECT_TRUE(
        std::regex_search(r.out, std::regex("Time +parse " + num + " s, build " + num +
                                            " s, render " + num + " s, write " + num + " s")))
        << r.out;
    // One camera ray per pixel: 64 x 48.
    EXPECT_TRUE(std::regex_search(
        r.out, std::regex("Rays +3072 camera, [0-9]+ shadow, [0-9]+ reflection, [0-9]+ total")))
        << r.out;
    EXPECT_TRUE(std::regex_search(r.out, std::regex("Throughput +" + num + " Mrays/s"))) << r.out;
    EXPECT_TRUE(contains(r.out, "Scene       2 triangles, 2 spheres, 2 lights")) << r.out;
}

TEST(Cli, StatsCountInstancedTrianglesOnce) {
    std::string dir = freshDir("instances");
    writeFile(dir + "/quad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n");
    writeFile(dir + "/scene.test",
              "size 32 24\ncamera 1.5 0.5 6 1.5 0.5 0 0 1 0 45\ndirectional 0 0 1 1 1 1\n"
              "diffuse 1 1 1\nmesh quad.obj\ntranslate 1 0 0\nmesh quad.obj\n"
              "translate 1 0 0\nmesh quad.obj\nsphere 0 0 -5 1\n");
    CommandResult r = runGlint("-q --stats scene.test", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(contains(r.out, "Scene       0 triangles, 1 sphere, 3 mesh instances, 1 light"))
        << r.out;
    EXPECT_TRUE(contains(
        r.out, "Instances   3 instances of 1 shared mesh: 6 triangles placed, 2 triangles stored"))
        << r.out;
    EXPECT_TRUE(std::regex_search(r.out, std::regex("BVH .* MB \\+ shared meshes [0-9.]+ MB")))
        << r.out;
}

TEST(Cli, QuietPrintsNothingOnStderrOnSuccess) {
    std::string dir = sceneDir("quiet");
    CommandResult loud = runGlint("scene.test", dir);
    ASSERT_EQ(loud.exitCode, 0);
    EXPECT_TRUE(contains(loud.err, "glint: wrote scene.png (64x48)")) << loud.err;

    fs::remove(dir + "/scene.png");
    CommandResult quiet = runGlint("-q scene.test", dir);
    EXPECT_EQ(quiet.exitCode, 0);
    EXPECT_EQ(quiet.err, "");
    EXPECT_EQ(quiet.out, "");
    EXPECT_TRUE(fs::exists(dir + "/scene.png"));
}

TEST(Cli, QuietStillPrintsWarnings) {
    std::string dir = freshDir("quietwarn");
    writeFile(dir + "/w.test", std::string(kScene) + "maxdepth 99\n");
    CommandResult r = runGlint("--quiet w.test", dir);
    EXPECT_EQ(r.exitCode, 0);
    EXPECT_EQ(r.err, "w.test:19:10: warning: maxdepth 99 is more than Glint traces; using 64\n");
}

TEST(Cli, ProgressOnANonTerminalIsPlainLinesEndingWithRendered) {
    std::string dir = sceneDir("progress");
    CommandResult r = runGlint("scene.test", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_FALSE(contains(r.err, "\r")) << "carriage return on a non-terminal";
    EXPECT_FALSE(contains(r.err, "\x1b")) << "escape sequence on a non-terminal";
    std::vector<std::string> l = lines(r.err);
    ASSERT_GE(l.size(), 2u) << r.err;
    EXPECT_TRUE(std::regex_match(l[l.size() - 2], std::regex("glint: rendered in [0-9.]+ s")))
        << r.err;
    EXPECT_EQ(l.back(), "glint: wrote scene.png (64x48)");
    for (size_t i = 0; i + 2 < l.size(); ++i)
        EXPECT_TRUE(l[i].rfind("glint: rendering ", 0) == 0) << l[i];
}

// ---- Information and usage errors ----

TEST(Cli, VersionPrintsTheVersionAndTraversalKernelsAndExitsZero) {
    CommandResult r = runGlint("--version", freshDir("version"));
    EXPECT_EQ(r.exitCode, 0);
    EXPECT_TRUE(std::regex_match(
        r.out,
        std::regex(
            "glint [0-9]+\\.[0-9]+\\.[0-9]+ \\(traversal kernels: (avx2|portable); denoiser: "
            "(oidn, OIDN 2\\.3's weights, (avx512|avx2|portable) kernels|nlm \\(no network "
            "weights: denoise-weights/README\\.md\\))\\)\n")))
        << r.out;
}

TEST(Cli, HelpShowsOptionGroupsAndExitsZero) {
    std::string dir = freshDir("help");
    for (const char* flag : {"--help", "-h"}) {
        SCOPED_TRACE(flag);
        CommandResult r = runGlint(flag, dir);
        EXPECT_EQ(r.exitCode, 0);
        for (const char* text :
             {"Usage: glint [OPTIONS] [SCENE]", "Output:", "Rendering:", "Information:",
              "-o,--output", "-t,--threads", "--size", "--maxdepth", "--check", "--stats",
              "-q,--quiet", "--version", "glint merge -o OUT", "glint denoise IN.exr -o OUT"})
            EXPECT_TRUE(contains(r.out, text)) << text << " missing from:\n" << r.out;
    }
    EXPECT_EQ(filesIn(dir), std::vector<std::string>{});
}

TEST(Cli, UnknownFlagIsAUsageError) {
    CommandResult r = runGlint("--no-such-flag", freshDir("badflag"));
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_TRUE(contains(r.err, "no-such-flag")) << r.err;
}

TEST(Cli, SecondSceneArgumentIsAUsageError) {
    std::string dir = sceneDir("twoscenes");
    CommandResult r = runGlint("scene.test other.test", dir);
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_EQ(r.err,
              "glint: error: one SCENE only, got 'scene.test' and 'other.test'\n"
              "Run 'glint --help' for usage.\n");
    EXPECT_EQ(filesIn(dir), std::vector<std::string>{"scene.test"});
}

// Misspelt options get the nearest option's name, in the words of the scene parser's "did you
// mean"; one letter alone is not guessed at.
TEST(Cli, MisspeltOptionsSuggestTheNearestOne) {
    const std::string dir = freshDir("misspelt");
    const struct {
        const char* args;
        const char* message;
    } cases[] = {
        {"--sampels 4", "unknown option '--sampels': did you mean '--samples'?"},
        {"--srbg", "unknown option '--srbg': did you mean '--srgb'?"},
        {"--maxdepht 3", "unknown option '--maxdepht': did you mean '--maxdepth'?"},
        {"-denoise",
         "unknown option '-denoise': did you mean '--denoise'? (long options take two dashes)"},
        {"--no-such-flag", "unknown option '--no-such-flag'"},
        {"-x", "unknown option '-x'"},
        {"--spp", "option --spp needs a value: N"},
        {"--srgb --tonemapp neutral", "unknown option '--tonemapp': did you mean '--tonemap'?"},
    };
    for (const auto& c : cases) {
        const CommandResult r = runGlint(c.args, dir);
        EXPECT_EQ(r.exitCode, 2) << c.args;
        EXPECT_EQ(r.err,
                  std::string("glint: error: ") + c.message + "\nRun 'glint --help' for usage.\n")
            << c.args;
    }
    // Every program's usage errors read the same way.
    CommandResult r = runGlint("merge --quite -o x.exr a.exr", dir);
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_EQ(r.err,
              "glint merge: error: unknown option '--quite': did you mean '--quiet'?\n"
              "Run 'glint merge --help' for usage.\n");
    r = runGlint("denoise in.exr other.exr -o out.exr", dir);
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_TRUE(contains(r.err,
                         "glint denoise: error: one INPUT only, got 'in.exr' and "
                         "'other.exr'"))
        << r.err;
    EXPECT_EQ(filesIn(dir), std::vector<std::string>{});
}

// docs/cli.md shows the whole of `glint --help`: it must be what the program prints.
TEST(Cli, TheHelpInDocsCliMdIsTheProgramsHelp) {
    const std::string doc = readBytes(std::string(GLINT_SOURCE_DIR) + "/docs/cli.md");
    const std::string begin = "<!-- glint --help -->\n```\n", end = "```\n<!-- end -->";
    const size_t a = doc.find(begin), b = doc.find(end, a);
    ASSERT_NE(a, std::string::npos) << "docs/cli.md has no '<!-- glint --help -->' block";
    ASSERT_NE(b, std::string::npos);
    // The kernels this CPU runs are the one thing that differs between machines.
    const std::regex machine("the best this CPU runs: [a-z0-9]+ here");
    const std::string shown = std::regex_replace(doc.substr(a + begin.size(), b - a - begin.size()),
                                                 machine, "the best this CPU runs");
    const CommandResult r = runGlint("--help", freshDir("helpdoc"));
    ASSERT_EQ(r.exitCode, 0);
    EXPECT_EQ(shown, std::regex_replace(r.out, machine, "the best this CPU runs"))
        << "regenerate docs/cli.md's copy with: build/glint --help";
}

TEST(Cli, MissingSceneFileExitsOneWithCannotRead) {
    std::string dir = freshDir("missing");
    CommandResult r = runGlint("nowhere/none.test", dir);
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_EQ(r.err, "nowhere/none.test: error: cannot read scene: No such file or directory\n");
    EXPECT_EQ(filesIn(dir), std::vector<std::string>{});

    fs::create_directories(dir + "/adir");
    r = runGlint("adir", dir);
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_EQ(r.err, "adir: error: cannot read scene: it is a directory\n");
}

// ---- Writing the image ----

TEST(Cli, OutputInAMissingDirectoryExitsOneWithAClearMessage) {
    std::string dir = sceneDir("nodir");
    CommandResult r = runGlint("-q scene.test -o missing/out.png", dir);
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_TRUE(contains(r.err, "glint: error: cannot write 'missing/out.png'")) << r.err;
    EXPECT_TRUE(contains(r.err, "No such file or directory")) << r.err;
    EXPECT_FALSE(fs::exists(dir + "/missing"));
}

TEST(Cli, ExistingOutputIsUnchangedWhenTheSceneFailsToParse) {
    std::string dir = freshDir("keepparse");
    writeFile(dir + "/bad.test", std::string(kScene) + "sphere 0 0 0\n");
    writeFile(dir + "/bad.png", "precious bytes");
    CommandResult r = runGlint("-q bad.test", dir);
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_EQ(readBytes(dir + "/bad.png"), "precious bytes");
}

TEST(Cli, ExistingOutputIsUnchangedWhenWritingFails) {
    // A file-size limit of one block makes the write fail part way (EFBIG, with SIGXFSZ
    // ignored); the old image must survive and no temporary file may be left behind.
    std::string dir = sceneDir("keepwrite");
    writeFile(dir + "/out.ppm", "precious bytes");
    std::string cmd = "cd '" + dir + "' && trap '' XFSZ && ulimit -f 1 && exec '" +
                      std::string(GLINT_BINARY) +
                      "' -q scene.test -o out.ppm >/dev/null 2>err.txt </dev/null";
    int status = std::system(cmd.c_str());
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 1) << status;
    std::string err = readBytes(dir + "/err.txt");
    EXPECT_TRUE(contains(err, "glint: error: cannot write 'out.ppm'")) << err;
    EXPECT_EQ(readBytes(dir + "/out.ppm"), "precious bytes");
    EXPECT_EQ(filesIn(dir), (std::vector<std::string>{"err.txt", "out.ppm", "scene.test"}));
}

}  // namespace
}  // namespace glint::test
