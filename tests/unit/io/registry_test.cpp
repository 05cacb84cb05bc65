// The registry: which loader a file gets, by its first bytes where they tell, else by its
// extension, else by what the caller wants; and one message for what Glint cannot read.

#include "glint/io/registry.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

#include "unit/test_support.h"

namespace glint {
namespace {

using ::testing::HasSubstr;
using namespace std::string_literals;

const std::string kReads =
    "; it reads CSE167x scenes (.test), OBJ (.obj), glTF (.gltf, .glb), PLY (.ply) and STL (.stl)";
const std::string kFbx =
    "Glint cannot read FBX files (export it as glTF, e.g. from Blender: File > Import > FBX, File "
    "> Export > glTF 2.0)";
const std::string kReadsMeshes =
    "; it reads meshes from OBJ (.obj), glTF (.gltf, .glb), PLY (.ply) and STL (.stl)";

struct Choice {
    std::string format;  ///< The chosen format's name, or "" for none.
    std::string problem;
    std::vector<Diagnostic> warnings;
};

Choice choose(const std::string& path, std::string_view head, FileUse use = FileUse::Scene,
              uint64_t size = 0) {
    Choice c;
    FormatChoice f = chooseFormat(path, head, size ? size : head.size(), use, c.warnings);
    c.format = f.format ? f.format->name : "";
    c.problem = f.problem;
    return c;
}

/// The first bytes of a binary STL file of `count` triangles (the header says "solid" too, as
/// some exporters write it).
std::string binaryStl(uint32_t count) {
    std::string s = "solid exported by a tool";
    s.resize(80, ' ');
    for (int i = 0; i < 4; ++i) s.push_back(static_cast<char>(count >> (8 * i) & 0xFF));
    s.append(50 * count, '\0');
    return s;
}

TEST(Registry, TextFilesAreWhatTheirExtensionSays) {
    EXPECT_EQ(choose("a.test", "size 10 10\n").format, "CSE167x scene");
    EXPECT_EQ(choose("a.OBJ", "v 0 0 0\n").format, "OBJ");
    EXPECT_EQ(choose("dir/a.gltf", "{\"asset\": {\"version\": \"2.0\"}}").format, "glTF");
}

TEST(Registry, TextOfNoKnownExtensionIsWhatTheCallerWants) {
    // `glint scene` reads a course scene; `mesh model.txt` an OBJ mesh, as before the registry.
    EXPECT_EQ(choose("scene", "size 10 10\ncamera 0 0 1 0 0 0 0 1 0 45\n").format, "CSE167x scene");
    EXPECT_EQ(choose("model.txt", "v 0 0 0\n", FileUse::Model).format, "OBJ");
    // An empty or unreadable file goes by its name, so that its loader says what is wrong.
    EXPECT_EQ(choose("missing.obj", "").format, "OBJ");
    EXPECT_EQ(choose("empty", "").format, "CSE167x scene");
}

TEST(Registry, PlyAndStlAreReadByTheirSignatureOrExtension) {
    EXPECT_EQ(choose("cow.ply", "ply\nformat ascii 1.0\nelement vertex 8\n").format, "PLY");
    EXPECT_EQ(choose("cow.PLY", "ply\r\nformat binary_little_endian 1.0\r\n").format, "PLY");
    EXPECT_EQ(choose("cow.ply", "ply\n", FileUse::Model).format, "PLY");
    EXPECT_EQ(choose("part.stl", "solid part\n  facet normal 0 0 1\n").format, "STL");
    EXPECT_EQ(choose("part.stl", binaryStl(2)).format, "STL");
    EXPECT_EQ(choose("part.stl", binaryStl(2), FileUse::Model).format, "STL");
    // A binary STL is known by its size (84 + 50 bytes per triangle), whatever its name or
    // header; a file of another size named .stl goes to the STL reader, which says what is
    // wrong.
    EXPECT_EQ(choose("download", binaryStl(3)).format, "STL");
    std::string header = binaryStl(0).substr(0, 80);
    header[0] = '\x01';
    EXPECT_EQ(choose("part.stl", header + "\x05\0\0\0"s).format, "STL");
    EXPECT_EQ(choose("part.bin", header + "\x05\0\0\0"s).format, "");
}

TEST(Registry, FormatsGlintCannotReadGetOneMessage) {
    EXPECT_EQ(choose("rig.fbx", "Kaydara FBX Binary  \0\x1a\0"s).problem, kFbx + kReads);
    EXPECT_EQ(choose("rig.fbx", "; FBX 7.4.0 project file\n").problem, kFbx + kReads);
    EXPECT_EQ(choose("rig.fbx", "not what it seems\n").problem,  // by its extension alone
              kFbx + kReads);
    EXPECT_EQ(choose("room.blend", "BLENDER-v300").problem,
              "Glint cannot read Blender files (export it as glTF from Blender: File > Export > "
              "glTF 2.0)" +
                  kReads);
    // Inside a scene, `mesh rig.fbx` lists what `mesh` reads.
    EXPECT_EQ(choose("rig.fbx", "Kaydara FBX Binary  \0"s, FileUse::Model).problem,
              kFbx + kReadsMeshes);
}

TEST(Registry, ContentsWinOverAnExtensionThatLies) {
    // The signature of a foreign format, whatever the name: never parsed as a scene.
    EXPECT_EQ(choose("rig.test", "Kaydara FBX Binary  \0"s).problem, kFbx + kReads);
    Choice ply = choose("cow.test", "ply\nformat ascii 1.0\n");
    EXPECT_EQ(ply.format, "PLY");
    ASSERT_EQ(ply.warnings.size(), 1u);
    EXPECT_EQ(ply.warnings[0].message,
              "the file is PLY, whatever its name says: it is read as PLY");
    EXPECT_EQ(choose("scene.test", "solid cube\nfacet normal 0 0 1\n").format, "STL");
    EXPECT_EQ(choose("model.obj", binaryStl(1), FileUse::Model).format, "STL");
    // A readable format is read as what it is, with a warning.
    Choice glb = choose("scene.test", "glTF\x02\0\0\0"s);
    EXPECT_EQ(glb.format, "glTF");
    ASSERT_EQ(glb.warnings.size(), 1u);
    EXPECT_EQ(glb.warnings[0].format("warning"),
              "scene.test: warning: the file is glTF, whatever its name says: it is read as glTF");
    // No warning where the name says nothing.
    EXPECT_TRUE(choose("download", "glTF\x02\0\0\0"s).warnings.empty());
}

TEST(Registry, BinaryFilesAreNeverParsedAsText) {
    const std::string elf("\x7f\x45\x4c\x46\x02\x01\x01\0\0\0", 10);  // an executable
    EXPECT_EQ(choose("a.out", elf).problem,
              "Glint cannot read this file: it is binary, of no format Glint knows" + kReads);
    EXPECT_EQ(
        choose("scene.test", elf).problem,
        "Glint cannot read this file: it is binary, and CSE167x scene files are text" + kReads);
    EXPECT_EQ(choose("model.obj", elf, FileUse::Model).problem,
              "Glint cannot read this file: it is binary, and OBJ files are text" + kReadsMeshes);
    // Without a NUL: control characters in more than 1 byte of 32.
    std::string noisy(64, 'a');
    noisy[5] = '\x01';
    noisy[9] = '\x02';
    noisy[20] = '\x03';
    EXPECT_EQ(choose("x.test", noisy).format, "");
    noisy[20] = 'a';  // two in 64: still text (a stray byte is the parser's to report)
    EXPECT_EQ(choose("x.test", noisy).format, "CSE167x scene");
    // UTF-8 and a byte-order mark are text.
    EXPECT_EQ(choose("x.test", "\xEF\xBB\xBF# caf\xC3\xA9\nsize 1 1\n").format, "CSE167x scene");
}

TEST(Registry, ASceneFileIsNotAMesh) {
    EXPECT_EQ(choose("other.test", "size 1 1\n", FileUse::Model).problem,
              "a CSE167x scene is not a mesh" + kReadsMeshes);
}

class RegistryFiles : public test::TempDirTest {};

TEST_F(RegistryFiles, LoadingAFileGlintCannotReadNamesIt) {
    std::string file = path("rig.fbx");
    std::ofstream(file, std::ios::binary) << "Kaydara FBX Binary  \0\x1a\0"s;
    std::vector<Diagnostic> warnings;
    try {
        loadSceneFile(file, warnings);
        FAIL() << "no SceneError";
    } catch (const SceneError& e) {
        EXPECT_EQ(e.diagnostic().loc.file, file);
        EXPECT_EQ(e.diagnostic().loc.line, 0);
        EXPECT_THAT(e.diagnostic().message, HasSubstr(kFbx));
    }
    EXPECT_THROW(loadModel(file, warnings), SceneError);
    // chooseFormat reads the first bytes: a glTF binary named .test is glTF.
    std::string glb = path("model.test");
    std::ofstream(glb, std::ios::binary) << "glTF\x02\0\0\0\x0c\0\0\0"s;
    FormatChoice c = chooseFormat(glb, FileUse::Scene, warnings);
    ASSERT_TRUE(c.format);
    EXPECT_STREQ(c.format->name, "glTF");
}

TEST_F(RegistryFiles, ASequenceReadsAStillMeshFileOnce) {
    // A scene whose `mesh` moves over time, and the mesh as a model file: frames loaded with
    // one cache read the file once (a change to it after the first frame is not seen); without
    // the cache, every frame reads it.
    std::string mesh = path("tri.obj");
    std::ofstream(mesh) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    std::string scene = path("s.test");
    std::ofstream(scene) << "camera 0 0 4 0 0 0 0 1 0 45\nmotion 1 0 0\nmesh tri.obj\n";
    AssetCache assets;
    LoadOptions options;
    options.assets = &assets;
    std::vector<Diagnostic> warnings;
    auto lowestX = [&](const std::string& file, double seconds) {
        options.time.seconds = seconds;
        return loadSceneFile(file, warnings, options).scene->primitives.bounds().lo.x;
    };
    const float scene0 = lowestX(scene, 0), model0 = lowestX(mesh, 0);
    std::ofstream(mesh) << "v 10 0 0\nv 11 0 0\nv 10 1 0\nf 1 2 3\n";
    EXPECT_EQ(lowestX(scene, 1), scene0 + 1);  // moved by the motion, as first read
    EXPECT_EQ(lowestX(mesh, 1), model0);
    options.assets = nullptr;
    EXPECT_EQ(lowestX(scene, 1), scene0 + 11);  // read again
}

}  // namespace
}  // namespace glint

namespace glint {
namespace {

TEST_F(RegistryFiles, AModelGetsTheStudioAndASceneFileKeepsTheCoursesSettings) {
    // A model: the studio look, unless the options ask for the classic one.
    std::string model = path("tri.obj");
    std::ofstream(model) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    std::vector<Diagnostic> warnings;
    ModelScene m = loadSceneFile(model, warnings);
    EXPECT_TRUE(m.framed);
    EXPECT_EQ(m.scene->integrator, "path");
    EXPECT_EQ(m.scene->spp, kStudioSpp);
    EXPECT_TRUE(m.scene->environment);
    EXPECT_TRUE(m.scene->shadowCatcher);
    EXPECT_EQ(m.scene->display, (DisplaySpec{ToneMap::PbrNeutral, true}));
    LoadOptions classic;
    classic.look = ModelLook::classic();
    m = loadSceneFile(model, warnings, classic);
    EXPECT_EQ(m.scene->integrator, "whitted");
    EXPECT_FALSE(m.scene->shadowCatcher);
    EXPECT_EQ(m.scene->display, DisplaySpec{});

    // A scene file: exactly what it says, whatever look a model would get.
    std::string scene = path("s.test");
    std::ofstream(scene) << "camera 0 0 4 0 0 0 0 1 0 45\nsphere 0 0 0 1\n";
    m = loadSceneFile(scene, warnings);
    EXPECT_FALSE(m.framed);
    EXPECT_EQ(m.note, "");
    EXPECT_EQ(m.scene->integrator, "whitted");
    EXPECT_EQ(m.scene->spp, 0);
    EXPECT_FALSE(m.scene->environment);
    EXPECT_FALSE(m.scene->shadowCatcher);
    EXPECT_EQ(m.scene->display, DisplaySpec{});
    EXPECT_TRUE(warnings.empty());
}

}  // namespace
}  // namespace glint
