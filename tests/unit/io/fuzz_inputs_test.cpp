// Every input the fuzzers start from (fuzz/corpus/course, obj, gltf, ply, stl) and
// every input they ever found a problem with (fuzz/regressions/...) goes through what the fuzz
// harness does, in every normal build: it parses or fails with a SceneError, and when it parses it
// renders with finite pixels.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "glint/io/course/course_loader.h"
#include "glint/io/gltf/gltf_loader.h"
#include "glint/io/obj/obj_loader.h"
#include "glint/io/ply/ply_loader.h"
#include "glint/io/stl/stl_loader.h"
#include "glint/render/renderer.h"
#include "glint/scene/model_framing.h"

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

/// Renders a prepared `scene` on one thread and expects every pixel to be finite.
void expectFinitePixels(const Scene& scene, const std::string& name) {
    RenderOptions o;
    o.threads = 1;
    Film f = render(scene, o).film;
    for (int y = 0; y < f.height(); ++y)
        for (int x = 0; x < f.width(); ++x)
            EXPECT_TRUE(isFinite(f.at(x, y))) << name << " pixel " << x << "," << y;
}

/// Parses `text` as the harness does; returns false for a clean SceneError. Renders a scene
/// that parses at a tiny size and expects every pixel to be finite.
bool parsesAndRendersFinite(const std::string& text, const std::string& name) {
    std::vector<Diagnostic> warnings;
    std::unique_ptr<Scene> scene;
    try {
        CourseOptions options;
        options.limits.readFiles = false;  // as the harness: no mesh or texture file is read
        options.lenient = text.size() % 2 == 1;
        scene = parseCourseScene(text, name, warnings, options);
    } catch (const SceneError&) {
        return false;
    }
    scene->width = std::min(scene->width, 8);
    scene->height = std::min(scene->height, 8);
    scene->maxDepth = std::min(scene->maxDepth, 3);
    scene->prepare();
    expectFinitePixels(*scene, name);
    return true;
}

std::string read(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

TEST(FuzzInputs, SeedCorpusParsesOrFailsCleanlyAndRendersFinite) {
    auto files = inputs("corpus/course");
    ASSERT_GT(files.size(), 10u) << "the seed corpus is missing";
    int parsed = 0;
    for (const auto& f : files) parsed += parsesAndRendersFinite(read(f), f.filename().string());
    // Many seeds are whole scenes that render; the others are fragments and broken files.
    EXPECT_GE(parsed, 10);
}

TEST(FuzzInputs, EveryRegressionFromFuzzingStaysFixed) {
    auto files = inputs("regressions/course");
    if (files.empty()) GTEST_SKIP() << "no fuzzing finding so far";
    for (const auto& f : files) parsesAndRendersFinite(read(f), f.filename().string());
}

/// What the model readers' harnesses do with one input (fuzz/fuzz_render.h,
/// loadAndRenderModel): `parse(input, warnings)` gives a Model; returns false for a clean
/// SceneError; a model that loads becomes the scene `glint model.EXT` makes, rendered tiny,
/// every pixel finite.
template <typename Parse>
bool modelLoadsAndRendersFinite(const std::string& input, const std::string& name, Parse parse) {
    std::vector<Diagnostic> warnings;
    Model model;
    try {
        model = parse(input, warnings);
    } catch (const SceneError&) {
        return false;
    }
    ModelScene m;
    try {
        m = frameModelScene(model, 8, 8);
    } catch (const SceneError&) {
        return true;
    }
    m.scene->maxDepth = 2;
    m.scene->prepare();
    expectFinitePixels(*m.scene, name);
    return true;
}

/// fuzz/obj_fuzzer.cpp: an OBJ text, optionally followed by "#mtl" and the MTL text.
bool objLoadsAndRendersFinite(const std::string& input, const std::string& name) {
    const std::string marker = "\n#mtl\n";
    std::string objText = input, mtl;
    ObjOptions options;
    options.limits.readFiles = false;
    if (size_t at = input.find(marker); at != std::string::npos) {
        objText = input.substr(0, at + 1);
        mtl = input.substr(at + marker.size());
        options.mtlText = &mtl;
    }
    return modelLoadsAndRendersFinite(objText, name, [&](const std::string& text, auto& warnings) {
        return singleMeshModel(parseObj(text, name, warnings, options));
    });
}

/// The options of the harnesses that limit memory: no file read, 64 MiB.
template <typename Options>
Options fuzzOptions() {
    Options options;
    options.limits.readFiles = false;
    options.limits.memoryBytes = size_t(64) << 20;
    return options;
}

bool gltfLoadsAndRendersFinite(const std::string& input, const std::string& name) {
    return modelLoadsAndRendersFinite(input, name, [&](const std::string& text, auto& warnings) {
        return parseGltf(text, name, warnings, fuzzOptions<GltfOptions>());
    });
}

bool plyLoadsAndRendersFinite(const std::string& input, const std::string& name) {
    return modelLoadsAndRendersFinite(input, name, [&](const std::string& text, auto& warnings) {
        return singleMeshModel(parsePly(text, name, warnings, fuzzOptions<PlyOptions>()));
    });
}

bool stlLoadsAndRendersFinite(const std::string& input, const std::string& name) {
    return modelLoadsAndRendersFinite(input, name, [&](const std::string& text, auto& warnings) {
        return singleMeshModel(parseStl(text, name, warnings, fuzzOptions<StlOptions>()));
    });
}

TEST(FuzzInputs, ObjSeedCorpusLoadsOrFailsCleanlyAndRendersFinite) {
    auto files = inputs("corpus/obj");
    ASSERT_GE(files.size(), 10u) << "the OBJ seed corpus is missing";
    int loaded = 0;
    for (const auto& f : files) loaded += objLoadsAndRendersFinite(read(f), f.filename().string());
    EXPECT_GE(loaded, 8);
}

TEST(FuzzInputs, EveryObjRegressionFromFuzzingStaysFixed) {
    auto files = inputs("regressions/obj");
    if (files.empty()) GTEST_SKIP() << "no fuzzing finding so far";
    for (const auto& f : files) objLoadsAndRendersFinite(read(f), f.filename().string());
}

TEST(FuzzInputs, GltfSeedCorpusLoadsOrFailsCleanlyAndRendersFinite) {
    auto files = inputs("corpus/gltf");
    ASSERT_GE(files.size(), 10u) << "the glTF seed corpus is missing";
    int loaded = 0;
    for (const auto& f : files) loaded += gltfLoadsAndRendersFinite(read(f), f.filename().string());
    EXPECT_GE(loaded, 9);
}

TEST(FuzzInputs, EveryGltfRegressionFromFuzzingStaysFixed) {
    auto files = inputs("regressions/gltf");
    if (files.empty()) GTEST_SKIP() << "no fuzzing finding so far";
    for (const auto& f : files) gltfLoadsAndRendersFinite(read(f), f.filename().string());
}

TEST(FuzzInputs, PlySeedCorpusLoadsOrFailsCleanlyAndRendersFinite) {
    auto files = inputs("corpus/ply");
    ASSERT_GE(files.size(), 10u) << "the PLY seed corpus is missing";
    int loaded = 0;
    for (const auto& f : files) loaded += plyLoadsAndRendersFinite(read(f), f.filename().string());
    EXPECT_GE(loaded, 8);
}

TEST(FuzzInputs, EveryPlyRegressionFromFuzzingStaysFixed) {
    auto files = inputs("regressions/ply");
    if (files.empty()) GTEST_SKIP() << "no fuzzing finding so far";
    for (const auto& f : files) plyLoadsAndRendersFinite(read(f), f.filename().string());
}

TEST(FuzzInputs, StlSeedCorpusLoadsOrFailsCleanlyAndRendersFinite) {
    auto files = inputs("corpus/stl");
    ASSERT_GE(files.size(), 10u) << "the STL seed corpus is missing";
    int loaded = 0;
    for (const auto& f : files) loaded += stlLoadsAndRendersFinite(read(f), f.filename().string());
    EXPECT_GE(loaded, 5);
}

TEST(FuzzInputs, EveryStlRegressionFromFuzzingStaysFixed) {
    auto files = inputs("regressions/stl");
    if (files.empty()) GTEST_SKIP() << "no fuzzing finding so far";
    for (const auto& f : files) stlLoadsAndRendersFinite(read(f), f.filename().string());
}

}  // namespace
}  // namespace glint
