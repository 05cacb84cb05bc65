// Every input the fuzzer starts from (fuzz/corpus/hw3) and every input it ever found a problem
// with (fuzz/regressions/hw3) goes through what the fuzz harness does, in every normal build:
// it parses or fails with a SceneError, and when it parses it renders with finite pixels.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "glint/io/hw3_loader.h"
#include "glint/render/renderer.h"

namespace glint {
namespace {

namespace fs = std::filesystem;

std::vector<fs::path> inputs(const char* sub) {
    std::vector<fs::path> files;
    fs::path dir = fs::path(GLINT_FUZZ_DIR) / sub;
    if (fs::exists(dir))
        for (const auto& e : fs::directory_iterator(dir))
            if (e.is_regular_file()) files.push_back(e.path());
    std::sort(files.begin(), files.end());
    return files;
}

/// Parses `text` as the harness does; returns false for a clean SceneError. Renders a scene
/// that parses at a tiny size and expects every pixel to be finite.
bool parsesAndRendersFinite(const std::string& text, const std::string& name) {
    std::vector<Diagnostic> warnings;
    std::unique_ptr<Scene> scene;
    try {
        scene = parseHw3Scene(text, name, warnings);
    } catch (const SceneError&) {
        return false;
    }
    scene->width = std::min(scene->width, 8);
    scene->height = std::min(scene->height, 8);
    scene->maxDepth = std::min(scene->maxDepth, 3);
    scene->prepare();
    RenderOptions o;
    o.threads = 1;
    Film f = render(*scene, o).film;
    for (int y = 0; y < f.height(); ++y)
        for (int x = 0; x < f.width(); ++x)
            EXPECT_TRUE(isFinite(f.at(x, y))) << name << " pixel " << x << "," << y;
    return true;
}

std::string read(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

TEST(FuzzInputs, SeedCorpusParsesOrFailsCleanlyAndRendersFinite) {
    auto files = inputs("corpus/hw3");
    ASSERT_GT(files.size(), 10u) << "the seed corpus is missing";
    int parsed = 0;
    for (const auto& f : files) parsed += parsesAndRendersFinite(read(f), f.filename().string());
    // Many seeds are whole scenes that render; the others are fragments and broken files.
    EXPECT_GE(parsed, 10);
}

TEST(FuzzInputs, EveryRegressionFromFuzzingStaysFixed) {
    auto files = inputs("regressions/hw3");
    if (files.empty()) GTEST_SKIP() << "no fuzzing finding so far";
    for (const auto& f : files) parsesAndRendersFinite(read(f), f.filename().string());
}

}  // namespace
}  // namespace glint
