// `glint model.ply` and `glint model.stl`: PLY and STL models rendered without a scene file,
// placed by the `mesh` command, and their errors as a user meets them (one line naming the file,
// exit code 1, no image). The files are written by the tests.

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <string>

#include "cli/cli_support.h"
#include "glint/io/image/image_io.h"

namespace glint::test {
namespace {

namespace fs = std::filesystem;

/// A square of side 2 in z = 0 and a triangle beside it, as binary little-endian PLY: two
/// faces, a quad and a triangle.
std::string binaryPly() {
    std::string s =
        "ply\nformat binary_little_endian 1.0\nelement vertex 5\nproperty float x\n"
        "property float y\nproperty float z\nelement face 2\n"
        "property list uchar int vertex_indices\nend_header\n";
    const float p[5][3] = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}, {2, -1, 0}};
    for (const auto& v : p) s.append(reinterpret_cast<const char*>(v), 12);
    auto face = [&](std::initializer_list<int32_t> ids) {
        s.push_back(static_cast<char>(ids.size()));
        for (int32_t i : ids) s.append(reinterpret_cast<const char*>(&i), 4);
    };
    face({0, 1, 2, 3});
    face({1, 4, 2});
    return s;
}

const char* kAsciiStl =
    "solid part\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   vertex 1 0 0\n"
    "   vertex 0 1 0\n  endloop\n endfacet\nendsolid part\n";

TEST(CliPlyStl, ABarePlyIsFramedAndRendered) {
    std::string dir = freshDir("ply-model");
    writeFile(dir + "/quad.ply", binaryPly());
    CommandResult r = runGlint("quad.ply --size 80x60 --spp 4", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(contains(r.err, "glint: quad.ply has no camera: framing it")) << r.err;
    EXPECT_TRUE(contains(r.err, "glint: wrote quad.png (80x60)")) << r.err;
    Image8 img = readImage8(dir + "/quad.png", 3);
    ASSERT_EQ(img.width, 80);
    // The mesh is in the middle of the picture: its pixel there is not the floor's.
    EXPECT_NE(img.at(40, 30, 0), img.at(2, 58, 0));
    r = runGlint("quad.ply --check", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(contains(r.out, "quad.ply: ok: 640x480, 3 triangles")) << r.out;
}

TEST(CliPlyStl, AnAsciiStlIsReadAndABinaryOneNamedSolidToo) {
    std::string dir = freshDir("stl-model");
    writeFile(dir + "/part.stl", kAsciiStl);
    CommandResult r = runGlint("part.stl --check", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(contains(r.out, "part.stl: ok: 640x480, 1 triangle,")) << r.out;
    // Binary, its header starting with "solid": read as binary.
    std::string bin = "solid binary";
    bin.resize(80, ' ');
    bin.append("\x01\0\0\0", 4);
    const float t[12] = {0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0};
    bin.append(reinterpret_cast<const char*>(t), 48);
    bin.append(2, '\0');
    writeFile(dir + "/bin.stl", bin);
    r = runGlint("bin.stl --check", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(contains(r.out, "bin.stl: ok: 640x480, 1 triangle,")) << r.out;
}

TEST(CliPlyStl, TheMeshCommandPlacesPlyAndStl) {
    std::string dir = freshDir("ply-mesh");
    writeFile(dir + "/quad.ply", binaryPly());
    writeFile(dir + "/part.stl", kAsciiStl);
    writeFile(dir + "/s.test",
              "size 40 30\ncamera 0 0 6 0 0 0 0 1 0 45\ndirectional 0 0 1 1 1 1\n"
              "diffuse 1 0 0\nmesh quad.ply\ntranslate 0 0 1\nmesh part.stl\n");
    CommandResult r = runGlint("s.test -q", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(r.err, "");
    Image8 img = readImage8(dir + "/s.png", 3);
    EXPECT_GT(img.at(15, 15, 0), 200);  // the red square
    EXPECT_EQ(img.at(1, 1, 0), 0);      // the background
}

TEST(CliPlyStl, TruncatedAndCorruptFilesNameTheFileAndExitOne) {
    std::string dir = freshDir("ply-errors");
    std::string ply = binaryPly();
    writeFile(dir + "/cut.ply", ply.substr(0, ply.size() - 6));
    CommandResult r = runGlint("cut.ply", dir);
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_EQ(r.err, "cut.ply: error: the file ends in face 1 of 2 (byte " +
                         std::to_string(ply.size() - 12) + "): is it complete?\n");
    EXPECT_FALSE(fs::exists(dir + "/cut.png"));

    std::string stl = kAsciiStl;
    stl.replace(stl.find("vertex 1 0 0"), 12, "vertex 1 x 0");
    writeFile(dir + "/bad.stl", stl);
    r = runGlint("bad.stl", dir);
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_EQ(r.err, "bad.stl:5:13: error: 'x' is not a number\n");

    // Through the mesh command, the error names the mesh file.
    writeFile(dir + "/s.test", "camera 0 0 5 0 0 0 0 1 0 45\nmesh cut.ply\n");
    r = runGlint("s.test", dir);
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_TRUE(contains(r.err, "cut.ply: error: the file ends in face 1 of 2")) << r.err;
    EXPECT_FALSE(fs::exists(dir + "/s.png"));
}

}  // namespace
}  // namespace glint::test
