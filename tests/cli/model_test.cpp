// `glint model.obj`: a bare OBJ model rendered without a scene file, and the `mesh` command as a
// user meets it. Models are copied from tests/data/meshes into a fresh directory per test.

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "cli/cli_support.h"
#include "glint/io/image/image_io.h"

namespace glint::test {
namespace {

namespace fs = std::filesystem;

const std::string kMeshes = std::string(GLINT_TEST_DATA_DIR) + "/meshes/";

/// A fresh directory holding copies of the named files from tests/data/meshes.
std::string dirWith(const std::string& name, std::initializer_list<const char*> files) {
    std::string dir = freshDir(name);
    for (const char* f : files) fs::copy_file(kMeshes + f, dir + "/" + f);
    return dir;
}

/// Pixels of `img` whose colour is close to (r, g, b).
int pixelsNear(const Image8& img, int r, int g, int b, int tolerance = 40) {
    int n = 0;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x)
            n += std::abs(img.at(x, y, 0) - r) <= tolerance &&
                 std::abs(img.at(x, y, 1) - g) <= tolerance &&
                 std::abs(img.at(x, y, 2) - b) <= tolerance;
    return n;
}

TEST(CliModel, ABareObjIsFramedAndRenderedToItsStemPng) {
    std::string dir = dirWith("model", {"flat.obj"});
    CommandResult r = runGlint("flat.obj --size 80x60 --spp 4", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(contains(r.err, "glint: flat.obj has no camera: framing it with a camera at ("))
        << r.err;
    EXPECT_TRUE(contains(r.err, "showing it in the studio environment with a ground shadow at y"))
        << r.err;
    EXPECT_TRUE(contains(r.err, "glint: wrote flat.png (80x60)")) << r.err;
    Image8 img = readImage8(dir + "/flat.png", 3);
    EXPECT_EQ(img.width, 80);
    EXPECT_EQ(img.height, 60);
    // The model is in the middle of the picture: its pixel there is not the ground's.
    EXPECT_NE(img.at(40, 30, 0), img.at(2, 58, 0));
}

TEST(CliModel, TheTexturedModelShowsItsTexels) {
    std::string dir = dirWith("textured", {"textured.obj", "textured.mtl", "quadrants.png"});
    CommandResult r = runGlint("-q textured.obj --size 96x72 -o out.png --integrator whitted", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(r.err, "");  // -q: not even the framing note
    Image8 img = readImage8(dir + "/out.png", 3);
    // The classic look. Each quadrant of the square shows its texel's colour: the square faces
    // +z, so the key and fill lights give it 0.75 x 0.537 + 0.3 x 0.512 = 0.556 of the texel,
    // plus the MTL ambient 0.1 (0.2 x Kd x the texture's mean): 0.656 -> 167 for a full
    // channel, 25 for an empty one.
    EXPECT_GT(pixelsNear(img, 167, 25, 25, 6), 20);
    EXPECT_GT(pixelsNear(img, 25, 167, 25, 6), 20);
    EXPECT_GT(pixelsNear(img, 25, 25, 167, 6), 20);
    EXPECT_GT(pixelsNear(img, 167, 167, 167, 6), 20);
    // In the studio the quadrants keep their colours: saturated red, green and blue, and a
    // white brighter than the grey around the square.
    r = runGlint("-q textured.obj --size 96x72 --spp 16 --no-denoise -o studio.png", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    img = readImage8(dir + "/studio.png", 3);
    auto dominant = [&](int c) {
        int n = 0;
        for (int y = 0; y < img.height; ++y)
            for (int x = 0; x < img.width; ++x) {
                int v = img.at(x, y, c), o1 = img.at(x, y, (c + 1) % 3),
                    o2 = img.at(x, y, (c + 2) % 3);
                n += v > 150 && o1 < 90 && o2 < 90;
            }
        return n;
    };
    EXPECT_GT(dominant(0), 20);
    EXPECT_GT(dominant(1), 20);
    EXPECT_GT(dominant(2), 20);
    EXPECT_GT(pixelsNear(img, 245, 245, 245, 10), 20);
}

TEST(CliModel, ExtensionIsCaseInsensitiveAndCheckSummarises) {
    std::string dir = freshDir("upper");
    fs::copy_file(kMeshes + "quad.obj", dir + "/QUAD.OBJ");
    CommandResult r = runGlint("QUAD.OBJ --check", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    // The studio: no plane and no light of Glint's (the environment lights it), and its
    // bounce limits.
    EXPECT_EQ(r.out,
              "QUAD.OBJ: ok: 640x480, 2 triangles, 0 spheres, 0 lights, maxdepth 12 (diffuse 8, "
              "glossy 8, transmission 12, volume 8), output QUAD.png\n");
    r = runGlint("QUAD.OBJ --check --integrator whitted", dir);
    EXPECT_EQ(r.out,
              "QUAD.OBJ: ok: 640x480, 2 triangles, 0 spheres, 1 plane, 2 lights, maxdepth 5, "
              "output QUAD.png\n");
}

TEST(CliModel, AMissingMaterialLibraryIsAWarningAndTheModelRenders) {
    std::string dir = dirWith("nomtl", {"missing-mtl.obj"});
    CommandResult r = runGlint("-q missing-mtl.obj --size 40x30 --spp 4", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(r.err,
              "missing-mtl.obj:1:8: warning: cannot read material library 'nowhere.mtl' "
              "(nowhere.mtl): No such file or directory; faces that use its materials take the "
              "default material\n");
    EXPECT_TRUE(fs::exists(dir + "/missing-mtl.png"));
}

TEST(CliModel, BrokenModelsAreErrorsNamingTheFileAndLine) {
    std::string dir = dirWith("broken", {"out-of-range.obj"});
    CommandResult r = runGlint("out-of-range.obj", dir);
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_TRUE(contains(r.err, "out-of-range.obj:5:7: error: vertex index '9' is out of range"))
        << r.err;
    r = runGlint("nowhere.obj", dir);
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_TRUE(contains(r.err, "nowhere.obj: error: cannot read mesh: No such file")) << r.err;
    EXPECT_FALSE(fs::exists(dir + "/nowhere.png"));
}

TEST(CliModel, AMissingTextureIsAWarningAndTheRenderGoesOn) {
    std::string dir = dirWith("notexture", {"missing-texture.obj", "missing-texture.mtl"});
    CommandResult r = runGlint("missing-texture.obj --size 40x30 --spp 4", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(contains(r.err,
                         "missing-texture.mtl:1:1: warning: material 'painted': cannot "
                         "read texture"))
        << r.err;
    EXPECT_TRUE(fs::exists(dir + "/missing-texture.png"));
}

TEST(CliModel, MeshCommandInASceneWithATransform) {
    std::string dir = dirWith("meshcmd", {"quad.obj"});
    writeFile(dir + "/scene.test",
              "size 40 40\ncamera 0 0 5 0 0 0 0 1 0 45\nambient 0 0 0\ndiffuse 1 0 0\n"
              "directional 0 0 1 1 1 1\n"
              "pushTransform\ntranslate -1 -1 0\nscale 2 2 1\nmesh quad.obj\npopTransform\n");
    CommandResult r = runGlint("-q scene.test", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    Image8 img = readImage8(dir + "/scene.png", 3);
    // The square, scaled to 2 x 2 and centred: red in the middle, black in the corners.
    EXPECT_EQ(img.at(20, 20, 0), 255);
    EXPECT_EQ(img.at(20, 20, 1), 0);
    EXPECT_EQ(img.at(0, 0, 0), 0);
    // A mesh that is missing is an error at the scene's line.
    writeFile(dir + "/bad.test", "camera 0 0 5 0 0 0 0 1 0 45\nmesh gone.obj\n");
    r = runGlint("bad.test", dir);
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_TRUE(contains(r.err, "bad.test:2:6: error: cannot read mesh 'gone.obj'")) << r.err;
}

}  // namespace
}  // namespace glint::test
