// Which files `glint FILE` and the scene command `mesh FILE` read: a file Glint cannot read gets
// one line naming what it reads and exit code 1, whatever its name; a file whose name lies is
// read as what it is.

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "cli/cli_support.h"

namespace glint::test {
namespace {

namespace fs = std::filesystem;
using namespace std::string_literals;

const std::string kReads =
    "; it reads CSE167x scenes (.test), OBJ (.obj), glTF (.gltf, .glb), PLY (.ply) and STL (.stl)";

struct UnreadableCase {
    const char* name;
    const char* file;
    std::string bytes;
    std::string message;  ///< After "<file>: error: ".
};

void PrintTo(const UnreadableCase& c, std::ostream* os) { *os << c.name; }

class UnreadableFile : public testing::TestWithParam<UnreadableCase> {};

TEST_P(UnreadableFile, GetsOneLineNamingWhatGlintReadsAndExitsOne) {
    const UnreadableCase& c = GetParam();
    std::string dir = freshDir(std::string("unreadable-") + c.name);
    writeFile(dir + "/" + c.file, c.bytes);
    CommandResult r = runGlint(c.file, dir);
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_EQ(r.err, std::string(c.file) + ": error: " + c.message + "\n");
    EXPECT_EQ(r.out, "");
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
}

const std::string kFbx =
    "Glint cannot read FBX files (export it as glTF, e.g. from Blender: File > Import > FBX, File "
    "> Export > glTF 2.0)";

const UnreadableCase kUnreadable[] = {
    {"BinaryFbx", "rig.fbx", "Kaydara FBX Binary  \0\x1a\0\xe8\x1c\0\0"s, kFbx + kReads},
    {"AsciiFbx", "rig.fbx", "; FBX 7.4.0 project file\nFBXHeaderExtension:  {\n", kFbx + kReads},
    {"BinaryFile", "photo.jpg", "\xff\xd8\xff\xe0\0\x10JFIF\0"s,
     "Glint cannot read this file: it is binary, of no format Glint knows" + kReads},
    {"BinaryNamedAsAScene", "scene.test", "\x1f\x8b\x08\0\0\0\0\0"s,
     "Glint cannot read this file: it is binary, and CSE167x scene files are text" + kReads},
    {"BinaryNamedAsObj", "model.obj", "\x1f\x8b\x08\0\0\0\0\0"s,
     "Glint cannot read this file: it is binary, and OBJ files are text" + kReads},
    {"FbxNamedAsAScene", "rig.test", "Kaydara FBX Binary  \0\x1a\0\xe8\x1c\0\0"s, kFbx + kReads},
};

INSTANTIATE_TEST_SUITE_P(Cli, UnreadableFile, testing::ValuesIn(kUnreadable),
                         [](const testing::TestParamInfo<UnreadableCase>& p) {
                             return std::string(p.param.name);
                         });

TEST(CliFormats, AGlbNamedAsASceneIsReadAsGltfWithAWarning) {
    std::string dir = freshDir("glb-as-test");
    fs::copy_file(std::string(GLINT_TEST_DATA_DIR) + "/gltf/quad.glb", dir + "/quad.test");
    CommandResult r = runGlint("quad.test --size 32x24", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.err.find("quad.test: warning: the file is glTF, whatever its name says: it is "
                         "read as glTF\n"),
              std::string::npos)
        << r.err;
    EXPECT_TRUE(fs::exists(dir + "/quad.png"));
}

TEST(CliFormats, ASceneWithoutExtensionIsAScene) {
    std::string dir = freshDir("no-extension");
    writeFile(dir + "/scene", "size 16 12\ncamera 0 0 5 0 0 0 0 1 0 45\nsphere 0 0 0 1\n");
    CommandResult r = runGlint("scene -q", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(r.err, "");
    EXPECT_TRUE(fs::exists(dir + "/scene.png"));
}

TEST(CliFormats, AMeshGlintCannotReadIsAnErrorAtTheMeshLine) {
    std::string dir = freshDir("mesh-fbx");
    writeFile(dir + "/rig.fbx", "; FBX 7.4.0 project file\n");
    writeFile(dir + "/s.test", "camera 0 0 5 0 0 0 0 1 0 45\n\n  mesh rig.fbx\n");
    CommandResult r = runGlint("s.test", dir);
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_EQ(r.err, "s.test:3:3: error: mesh 'rig.fbx': " + kFbx +
                         "; it reads meshes from OBJ (.obj), glTF (.gltf, .glb), PLY (.ply) and "
                         "STL (.stl)\n");
    writeFile(dir + "/s.test", "camera 0 0 5 0 0 0 0 1 0 45\nmesh other.test\n");
    writeFile(dir + "/other.test", "size 1 1\n");
    r = runGlint("s.test", dir);
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_EQ(r.err,
              "s.test:2:1: error: mesh 'other.test': a CSE167x scene is not a mesh; it reads "
              "meshes from OBJ (.obj), glTF (.gltf, .glb), PLY (.ply) and STL (.stl)\n");
}

}  // namespace
}  // namespace glint::test
