// The glTF loader's errors (io/gltf/gltf_loader.h): every one names the file, and the object at
// fault. Broken files are in tests/data/gltf (see PROVENANCE.md); variations are written here.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdint>
#include <fstream>
#include <string>

#include "glint/io/gltf/gltf_loader.h"
#include "unit/io/gltf/gltf_test_support.h"
#include "unit/test_support.h"

namespace glint {
namespace {

using namespace glint::test;
using ::testing::HasSubstr;

TEST(GltfErrors, OutOfRangeAccessor) {
    Diagnostic d = errorLoading("bad-accessor.gltf");
    EXPECT_EQ(d.loc.file, dataPath("bad-accessor.gltf"));
    EXPECT_EQ(d.message,
              "accessor 9 does not exist (the file has 4 accessors): NORMAL of mesh 0 'quad', "
              "primitive 0 refers to it");
}

TEST(GltfErrors, AccessorBeyondItsBufferView) {
    Diagnostic d = errorLoading("bad-accessor-range.gltf");
    EXPECT_EQ(d.loc.file, dataPath("bad-accessor-range.gltf"));
    EXPECT_THAT(d.message, HasSubstr("accessor 0 (POSITION of mesh 0 'quad', primitive 0): its 40 "
                                     "elements of 12 bytes"));
    EXPECT_THAT(d.message, HasSubstr("do not fit in bufferView 0 (48 bytes)"));
}

TEST(GltfErrors, BufferViewBeyondItsBuffer) {
    Diagnostic d = errorLoading("bad-bufferview.gltf");
    EXPECT_EQ(d.loc.file, dataPath("bad-bufferview.gltf"));
    EXPECT_EQ(d.message,
              "bufferView 1: its 4000 bytes from offset 48 lie beyond the end of buffer 0 (140 "
              "bytes)");
}

TEST(GltfErrors, IndexBeyondTheVertices) {
    Diagnostic d = errorLoading("bad-index.gltf");
    EXPECT_EQ(d.loc.file, dataPath("bad-index.gltf"));
    EXPECT_EQ(d.message,
              "accessor 1 (indices of mesh 0, primitive 0): index 5 is 7, but the primitive has 4 "
              "vertices");
}

TEST(GltfErrors, MissingBufferFile) {
    Diagnostic d = errorLoading("missing-bin.gltf");
    EXPECT_EQ(d.loc.file, dataPath("missing-bin.gltf"));
    EXPECT_EQ(d.message, "cannot read buffer file '" + dataPath("nowhere.bin") +
                             "': No such file or directory");
    GltfOptions off;
    off.limits.readFiles = false;
    std::vector<Diagnostic> warnings;
    try {
        loadGltf(dataPath("quad.gltf"), warnings, off);
        ADD_FAILURE() << "an external buffer was read with reading files off";
    } catch (const SceneError& e) {
        EXPECT_THAT(e.diagnostic().message, HasSubstr("is not read: reading files is off"));
    }
}

TEST(GltfErrors, TruncatedBinaryFile) {
    Diagnostic d = errorLoading("truncated.glb");
    EXPECT_EQ(d.loc.file, dataPath("truncated.glb"));
    EXPECT_EQ(d.message,
              "the file is truncated: its header gives its length as 1340 bytes, but it has 1300");
    auto u32 = [](uint32_t x) { return std::string(reinterpret_cast<const char*>(&x), 4); };
    std::string glb = "glTF" + u32(2);
    EXPECT_THAT(errorParsing(glb).message, HasSubstr("a binary glTF starts with a 12-byte header"));
    glb += u32(64) + u32(44) + "JSON" + std::string(44, ' ');
    glb.replace(16, 4, "NOSJ");
    EXPECT_THAT(errorParsing(glb).message, HasSubstr("its first chunk is not JSON"));
    glb.replace(16, 4, u32(0x4E4F534A));
    glb.replace(12, 4, u32(100));  // a JSON chunk longer than the file
    EXPECT_THAT(errorParsing(glb).message, HasSubstr("JSON chunk of 100 bytes does not fit"));
    glb.replace(4, 4, u32(1));
    EXPECT_THAT(errorParsing(glb).message, HasSubstr("binary glTF version 1 is not supported"));
}

TEST(GltfErrors, MissingFile) {
    Diagnostic d = errorLoading("nowhere.gltf");
    EXPECT_EQ(d.message, "cannot read glTF: No such file or directory");
}

TEST(GltfErrors, BadJsonAndStructure) {
    EXPECT_EQ(errorParsing("").message, "the file is empty");
    EXPECT_THAT(errorParsing("{\"asset\": ").message, HasSubstr("tinygltf: "));
    EXPECT_THAT(errorParsing(R"({"asset": {"version": "1.0"}})").message,
                HasSubstr("glTF version '1.0' is not supported"));
    EXPECT_THAT(errorParsing(std::string(600, '[') + std::string(600, ']')).message,
                HasSubstr("its JSON nests 600 levels deep, more than the 512"));
    EXPECT_THAT(errorParsing(gltfText(R"("extensionsRequired": ["KHR_texture_basisu"])")).message,
                HasSubstr("requires extension KHR_texture_basisu"));
    EXPECT_EQ(errorParsing(gltfText(R"("scenes": [{"nodes": [0]}], "scene": 1)")).message,
              "scene 1 does not exist (the file has 1 scene): the default scene ('scene') refers "
              "to it");
    EXPECT_EQ(errorParsing(gltfText(R"("nodes": [{"children": [3]}])")).message,
              "node 3 does not exist (the file has 1 node): node 0's children refers to it");
    EXPECT_EQ(errorParsing(gltfText(R"("nodes": [{"mesh": 2}])")).message,
              "mesh 2 does not exist (the file has 0 meshes): node 0 refers to it");
}

TEST(GltfErrors, ImagesInABufferViewBeyondItsBufferAreCaughtBeforeTinygltf) {
    // tinygltf 2.7 would form a pointer at the offset before checking it (fuzzing found this).
    std::string text = gltfText(
        R"("bufferViews": [{"buffer": 0, "byteOffset": 18446744073709551000, "byteLength": 4}],
           "images": [{"bufferView": 0, "mimeType": "image/png"}])",
        "AAAA");
    EXPECT_EQ(errorParsing(text).message,
              "bufferView 0: its 4 bytes from offset 18446744073709551000 lie beyond the end of "
              "buffer 0 (3 bytes)");
    // Spelling the key with an escape does not get past the check.
    text.replace(text.find("\"images\""), 8, "\"\\u0069mages\"");
    EXPECT_THAT(errorParsing(text).message, HasSubstr("lie beyond the end of buffer 0"));
}

TEST(GltfErrors, NodesFormTrees) {
    // Two parents: node 2 is reached twice from the scene's roots.
    std::string twoParents = gltfText(
        R"("nodes": [{"children": [2]}, {"children": [2]}, {}], "scenes": [{"nodes": [0, 1]}])");
    EXPECT_THAT(errorParsing(twoParents).message, HasSubstr("node 2 is reached twice"));
    std::string cycle =
        gltfText(R"("nodes": [{"children": [1]}, {"children": [0]}], "scenes": [{"nodes": [0]}])");
    EXPECT_THAT(errorParsing(cycle).message, HasSubstr("node 0 is reached twice"));
}

TEST(GltfErrors, NodeTransforms) {
    EXPECT_EQ(errorParsing(gltfText(R"("nodes": [{"matrix": [1, 0, 0]}])")).message,
              "node 0: 'matrix' must have 16 numbers, got 3");
    EXPECT_THAT(
        errorParsing(
            gltfText(R"("nodes": [{"name": "n", "matrix": [1,0,0,1, 0,1,0,0, 0,0,1,0, 0,0,0,1]}])"))
            .message,
        HasSubstr("node 0 'n': its matrix is not affine"));
    EXPECT_THAT(errorParsing(gltfText(R"("nodes": [{"rotation": [0, 0, 0, 0]}])")).message,
                HasSubstr("its rotation must be a non-zero quaternion"));
    // JSON has no infinity; a number beyond the double range is an error of the parser.
    EXPECT_THAT(errorParsing(gltfText(R"("nodes": [{"translation": [1e999, 0, 0]}])")).message,
                HasSubstr("number overflow parsing '1e999'"));
    // A scale of 0 hides a node: a warning, not an error.
    std::vector<Diagnostic> warnings;
    Model model = parse(gltfText(kTriangleScene.substr(0, kTriangleScene.rfind('[')) +
                                     R"([{"mesh": 0, "scale": [0, 1, 1]}])",
                                 kTriangle),
                        &warnings);
    EXPECT_TRUE(model.placements.empty());
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_THAT(warnings[0].message, HasSubstr("its transform is singular"));
}

TEST(GltfErrors, AccessorsAndTheirData) {
    auto withAccessor = [](const std::string& accessor) {
        return gltfText(R"("bufferViews": [{"buffer": 0, "byteLength": 36}], "accessors": [)" +
                            accessor +
                            R"(], "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
                          "nodes": [{"mesh": 0}])",
                        kTriangle);
    };
    EXPECT_THAT(
        errorParsing(
            withAccessor(R"({"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC2"})"))
            .message,
        HasSubstr("its elements are VEC2, not VEC3"));
    EXPECT_THAT(
        errorParsing(
            withAccessor(R"({"bufferView": 0, "componentType": 5127, "count": 3, "type": "VEC3"})"))
            .message,
        HasSubstr("component type 5127 is not one glTF defines"));
    EXPECT_THAT(
        errorParsing(
            withAccessor(
                R"({"bufferView": 0, "byteOffset": 18446744073709551615, "componentType": 5126, "count": 3, "type": "VEC3"})"))
            .message,
        HasSubstr("do not fit in bufferView 0"));
    EXPECT_THAT(
        errorParsing(
            withAccessor(
                R"({"bufferView": 0, "componentType": 5126, "count": 3074457345618258603, "type": "VEC3"})"))
            .message,
        HasSubstr("do not fit in bufferView 0"));
    // A NaN coordinate (0x7fc00000) where the first vertex's x was.
    std::string nan = "AADAfwAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA";
    EXPECT_THAT(errorParsing(gltfText(kTriangleScene, nan)).message,
                HasSubstr("accessor 0 (POSITION of mesh 0, primitive 0): element 0 is not a finite "
                          "position"));
}

TEST(GltfErrors, CopiesOfTheBinaryChunkCountAgainstTheMemory) {
    // tinygltf copies the binary chunk for each buffer without a URI: three 100 kB copies.
    std::string bin(100000, '\0');
    std::string one = R"({"asset": {"version": "2.0"}, "buffers": [{"byteLength": 100000}]})";
    std::string three = R"({"asset": {"version": "2.0"}, "buffers": [{"byteLength": 100000},
        {"byteLength": 100000}, {"byteLength": 100000}]})";
    GltfOptions options;
    options.limits.memoryBytes = 250000;
    std::vector<Diagnostic> warnings;
    EXPECT_NO_THROW(parseGltf(glbOf(one, bin), "t.glb", warnings, options));
    EXPECT_THAT(errorParsing(glbOf(three, bin), options).message,
                HasSubstr("reading it needs about"));
}

class GltfFiles : public test::TempDirTest {};

TEST_F(GltfFiles, EveryReadOfABufferFileCountsAgainstTheMemory) {
    std::ofstream(path("big.bin"), std::ios::binary) << std::string(100000, '\0');
    auto gltf = [&](int buffers) {
        std::string list;
        for (int i = 0; i < buffers; ++i)
            list += std::string(i ? ", " : "") + R"({"byteLength": 100000, "uri": "big.bin"})";
        std::ofstream(path("m.gltf")) << gltfText(R"("buffers": [)" + list + "]");
        return path("m.gltf");
    };
    GltfOptions options;
    options.limits.memoryBytes = 250000;
    std::vector<Diagnostic> warnings;
    EXPECT_NO_THROW(loadGltf(gltf(2), warnings, options));
    try {
        loadGltf(gltf(3), warnings, options);
        ADD_FAILURE() << "three copies of the buffer file were read";
    } catch (const SceneError& e) {
        EXPECT_THAT(e.diagnostic().message, HasSubstr("its buffer files take"));
    }
}

TEST(GltfErrors, ModelsTooLargeForTheMemoryGivenAreRefusedBeforeReading) {
    // 1000 triangles (of zeros: only their number matters), placed by 10 nodes.
    std::string zeros;
    for (int i = 0; i < 12000; ++i) zeros += "AAAA";
    std::string nodes;
    for (int i = 0; i < 10; ++i) nodes += std::string(i ? ", " : "") + R"({"mesh": 0})";
    std::string text = gltfText(R"("bufferViews": [{"buffer": 0, "byteLength": 36000}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3000, "type": "VEC3"}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}], "nodes": [)" +
                                    nodes + "]",
                                zeros);
    GltfOptions options;
    options.limits.memoryBytes = 300000;
    Diagnostic d = errorParsing(text, options);
    EXPECT_THAT(d.message, HasSubstr("the model needs about"));
    // Ten nodes place the mesh: it is stored once (instanced), and counted once.
    EXPECT_THAT(d.message, HasSubstr("(1000 triangles stored), more than the"));
    options.limits.memoryBytes = 1 << 20;  // ten copies would not fit; one stored copy does
    {
        std::vector<Diagnostic> warnings;
        EXPECT_EQ(parseGltf(text, "t.gltf", warnings, options).triangles(), 10000u);
    }
    options.limits.memoryBytes = 100000;  // less than parsing the JSON takes
    EXPECT_THAT(errorParsing(text, options).message, HasSubstr("reading it needs about"));
    options.limits.memoryBytes = 0;  // the machine's: it loads
    std::vector<Diagnostic> warnings;
    EXPECT_EQ(parseGltf(text, "t.gltf", warnings, options).triangles(), 10000u);
}

}  // namespace
}  // namespace glint
