// `glint model.gltf` and `glint model.glb` as a user meets them: the file's camera and lights,
// Glint's framing for what is missing, and bad files. Files are copied from tests/data/gltf
// into a fresh directory per test.

#include <gtest/gtest.h>

#include <array>
#include <filesystem>
#include <string>

#include "cli/cli_support.h"
#include "glint/io/image/image_io.h"
#include "unit/io/gltf/gltf_asset_builder.h"

namespace glint::test {
namespace {

namespace fs = std::filesystem;

const std::string kGltf = std::string(GLINT_TEST_DATA_DIR) + "/gltf/";

/// A fresh directory holding copies of the named files from tests/data/gltf.
std::string dirWith(const std::string& name, std::initializer_list<const char*> files) {
    std::string dir = freshDir(name);
    for (const char* f : files) fs::copy_file(kGltf + f, dir + "/" + f);
    return dir;
}

TEST(CliGltf, AFileWithCameraAndLightsRendersAsItSaysAtItsAspectRatio) {
    std::string dir = dirWith("gltf-scene", {"scene.glb"});
    CommandResult r = runGlint("scene.glb --spp 1", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_FALSE(contains(r.err, "has no")) << r.err;  // nothing was missing ...
    // ... and the studio environment and a ground shadow were added to what it has.
    EXPECT_TRUE(contains(r.err,
                         "glint: showing scene.glb in the studio environment with a ground shadow "
                         "at y = "))
        << r.err;
    EXPECT_TRUE(contains(r.err, "(and its camera 0 ")) << r.err;
    EXPECT_TRUE(contains(r.err, " and 2 lights of its own)")) << r.err;
    EXPECT_TRUE(contains(r.err, "glint: wrote scene.png (640x360)")) << r.err;
    Image8 img = readImage8(dir + "/scene.png", 3);
    EXPECT_EQ(img.height, 360);
    r = runGlint("scene.glb --check --size 100x50", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(r.out,
              "scene.glb: ok: 100x50, 530 triangles, 0 spheres, 2 mesh instances, 2 lights, "
              "maxdepth 12 (diffuse 8, glossy 8, transmission 12, volume 8), output scene.png\n"
              "extensions used (1):\n"
              "  KHR_lights_punctual  rendered\n");
    // The classic look: the file's camera and lights alone, nothing said.
    r = runGlint("scene.glb --integrator whitted --size 64x36", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_FALSE(contains(r.err, "showing")) << r.err;
}

TEST(CliGltf, AVariantTheFileDoesNotHaveIsAnErrorAndCheckListsThem) {
    std::string dir = dirWith("gltf-variant", {"quad.gltf", "quad.bin", "quadrants.png"});
    CommandResult r = runGlint("quad.gltf --variant Blue --size 16x12 --spp 1", dir);
    EXPECT_EQ(r.exitCode, 1) << r.err;
    EXPECT_TRUE(contains(r.err,
                         "--variant Blue: no such material variant: the file has no "
                         "material variants"))
        << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir + "/quad.png"));  // nothing written
}

TEST(CliGltf, AnAlmostBlackImageIsWarnedOfWithWhatToTry) {
    // The file's camera inside a closed box, no lights: the studio cannot light the inside.
    std::string dir = dirWith("gltf-dark", {"closed-room.gltf"});
    CommandResult r = runGlint("closed-room.gltf --size 32x24 --spp 2", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(contains(r.err, "glint: warning: the image is almost black")) << r.err;
    EXPECT_TRUE(contains(r.err, "--camera none")) << r.err;
    // Glint's framing, from outside the box, in the studio: lit, nothing said.
    r = runGlint("closed-room.gltf --camera none --size 32x24 --spp 2", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_FALSE(contains(r.err, "almost black")) << r.err;
}

TEST(CliGltf, ABareModelIsFramedAndSaysSo) {
    std::string dir = dirWith("gltf-bare", {"quad.gltf", "quad.bin", "quadrants.png"});
    CommandResult r = runGlint("quad.gltf --size 80x60 --spp 4", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(contains(r.err, "glint: quad.gltf has no camera: framing it with a camera at ("))
        << r.err;
    EXPECT_TRUE(contains(r.err, "and showing it in the studio environment with a ground shadow"))
        << r.err;
    EXPECT_TRUE(fs::exists(dir + "/quad.png"));
    r = runGlint("-q quad.gltf --size 80x60 --spp 4 -o q.png", dir);
    EXPECT_EQ(r.err, "");
    r = runGlint("quad.gltf --size 80x60 --integrator whitted -o c.png", dir);
    EXPECT_TRUE(
        contains(r.err, "glint: quad.gltf has no camera or lights: framing it with a camera at ("))
        << r.err;
    EXPECT_TRUE(contains(r.err, "a key and a fill directional light")) << r.err;
}

TEST(CliGltf, BadFilesAreErrorsNamingTheFile) {
    std::string dir = dirWith(
        "gltf-bad", {"bad-accessor.gltf", "truncated.glb", "missing-bin.gltf", "bad-index.gltf"});
    CommandResult r = runGlint("bad-accessor.gltf", dir);
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_TRUE(contains(r.err, "bad-accessor.gltf: error: accessor 9 does not exist")) << r.err;
    r = runGlint("truncated.glb", dir);
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_TRUE(contains(r.err, "truncated.glb: error: the file is truncated")) << r.err;
    r = runGlint("missing-bin.gltf", dir);
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_TRUE(contains(r.err,
                         "missing-bin.gltf: error: cannot read buffer file 'nowhere.bin': No such "
                         "file or directory"))
        << r.err;
    r = runGlint("bad-index.gltf", dir);
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_TRUE(contains(r.err,
                         "bad-index.gltf: error: accessor 1 (indices of mesh 0, "
                         "primitive 0): index 5 is 7"))
        << r.err;
    r = runGlint("NOWHERE.GLB", dir);
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_TRUE(contains(r.err, "NOWHERE.GLB: error: cannot read glTF: No such file")) << r.err;
    EXPECT_FALSE(fs::exists(dir + "/NOWHERE.png"));
}

TEST(CliGltf, AMissingTextureIsAWarning) {
    std::string dir = dirWith("gltf-notexture", {"missing-texture.gltf"});
    CommandResult r = runGlint("missing-texture.gltf --size 40x30", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(contains(r.err,
                         "missing-texture.gltf: warning: material 0 'painted': cannot read "
                         "texture 'nowhere.png'"))
        << r.err;
    EXPECT_TRUE(fs::exists(dir + "/missing-texture.png"));
}

TEST(CliGltf, MeshCommandPlacesAGltfFileRelativeToTheScene) {
    std::string dir = freshDir("gltf-meshcmd");
    fs::create_directories(dir + "/models");
    for (const char* f : {"quad.gltf", "quad.bin", "quadrants.png"})
        fs::copy_file(kGltf + f, dir + "/models/" + f);
    writeFile(dir + "/scene.test",
              "size 40 40\ncamera 0 0 5 0 0 0 0 1 0 45\nambient 0 0 0\n"
              "directional 0 0 1 1 1 1\n"
              "pushTransform\ntranslate -1 -1 0\nscale 2 2 1\nmesh models/quad.gltf\n"
              "popTransform\n");
    CommandResult r = runGlint("-q scene.test", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    Image8 img = readImage8(dir + "/scene.png", 3);
    // The textured square, scaled to 2 x 2 and centred: red at the top left, blue at the
    // bottom left (quadrants.png), black in the corners.
    EXPECT_GT(img.at(14, 14, 0), 200);
    EXPECT_LT(img.at(14, 14, 2), 50);
    EXPECT_GT(img.at(14, 26, 2), 200);
    EXPECT_LT(img.at(14, 26, 0), 50);
    EXPECT_EQ(img.at(0, 0, 0), 0);
}

/// Two quads, red around x = -3 and blue around x = 3, with camera 0 'Left' in front of the red
/// one and camera 1 'Right' (node 'right') in front of the blue one.
std::string twoCameras() {
    GltfAsset a;
    int red = a.floats({-4, -1, 0, -2, -1, 0, -2, 1, 0, -4, 1, 0}, "VEC3");
    int blue = a.floats({2, -1, 0, 4, -1, 0, 4, 1, 0, 2, 1, 0}, "VEC3");
    int indices = a.integers({0, 1, 2, 0, 2, 3}, GltfAsset::kUbyte, "SCALAR");
    auto quad = [&](int positions, int material) {
        return R"({"primitives": [{"attributes": {"POSITION": )" + std::to_string(positions) +
               R"(}, "indices": )" + std::to_string(indices) + R"(, "material": )" +
               std::to_string(material) + "}]}";
    };
    return a.text(R"("meshes": [)" + quad(red, 0) + ", " + quad(blue, 1) + R"(],
        "materials": [{"pbrMetallicRoughness": {"baseColorFactor": [1, 0, 0, 1], "metallicFactor": 0}},
                      {"pbrMetallicRoughness": {"baseColorFactor": [0, 0, 1, 1], "metallicFactor": 0}}],
        "cameras": [{"name": "Left", "type": "perspective", "perspective": {"yfov": 0.5, "znear": 0.1}},
                    {"name": "Right", "type": "perspective", "perspective": {"yfov": 0.5, "znear": 0.1}}],
        "nodes": [{"mesh": 0}, {"mesh": 1}, {"camera": 0, "translation": [-3, 0, 5]},
                  {"name": "right", "camera": 1, "translation": [3, 0, 5]}])");
}

TEST(CliGltf, CameraPicksOneOfTheFilesCameras) {
    std::string dir = freshDir("gltf-cameras");
    writeFile(dir + "/two.gltf", twoCameras());
    auto centre = [&](const std::string& args) {
        CommandResult r = runGlint("-q two.gltf --size 9x9 -o c.png " + args, dir);
        EXPECT_EQ(r.exitCode, 0) << r.err;
        Image8 img = readImage8(dir + "/c.png", 3);
        return std::array<int, 3>{img.at(4, 4, 0), img.at(4, 4, 1), img.at(4, 4, 2)};
    };
    auto left = centre("");  // the first camera
    EXPECT_GT(left[0], left[2] + 50);
    for (const char* choice : {"1", "Right", "right"}) {
        auto right = centre(std::string("--camera ") + choice);
        EXPECT_GT(right[2], right[0] + 50) << choice;
    }
}

TEST(CliGltf, CameraNoneFramesTheModelAndSaysSo) {
    std::string dir = dirWith("gltf-camera-none", {"scene.glb"});
    CommandResult r = runGlint("scene.glb --camera none --size 40x30", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(contains(r.err, "glint: scene.glb has no camera: framing it with a camera at ("))
        << r.err;
    EXPECT_TRUE(contains(r.err, "(and 2 lights of its own)")) << r.err;
}

TEST(CliGltf, AnUnknownCameraIsAnErrorListingTheCameras) {
    std::string dir = dirWith("gltf-camera-bad", {"scene.glb"});
    CommandResult r = runGlint("scene.glb --camera 3", dir);
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_TRUE(contains(r.err,
                         "scene.glb: error: there is no camera 3 (cameras are numbered from 0 in "
                         "the order of the node tree): the file has 1 camera: 0 = camera 0 "
                         "'view' (node 3 'camera')"))
        << r.err;
    r = runGlint("scene.glb --camera Front", dir);
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_TRUE(contains(r.err, "scene.glb: error: no camera or camera node is named 'Front'"))
        << r.err;
    EXPECT_FALSE(fs::exists(dir + "/scene.png"));
    // Scene files and the demo have their own camera; an empty choice is no choice.
    writeFile(dir + "/s.test", "size 8 8\ncamera 0 0 5 0 0 0 0 1 0 45\nsphere 0 0 0 1\n");
    r = runGlint("s.test --camera 0", dir);
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_TRUE(contains(r.err,
                         "s.test: error: a CSE167x scene has the camera its commands "
                         "define: choosing one of a file's cameras (--camera) is for model "
                         "files"))
        << r.err;
    r = runGlint("--camera 0", dir);
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_TRUE(contains(r.err, "--camera chooses a model file's camera")) << r.err;
    r = runGlint("scene.glb --camera ''", dir);
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_TRUE(contains(r.err, "expected a camera number, a name, none or orbit:...")) << r.err;
    for (const char* bad : {"orbit:1,2", "orbit:0,0,1", "orbit:0,90,0", "orbit:0,90,1,x,0,0"}) {
        r = runGlint(std::string("scene.glb --camera ") + bad, dir);
        EXPECT_EQ(r.exitCode, 2) << bad;
        EXPECT_TRUE(contains(r.err, "glint: error: --camera: ")) << r.err;
    }
}

TEST(CliGltf, AnOrbitCameraLooksAtItsTargetWithTheFieldOfViewAsked) {
    std::string dir = freshDir("gltf-orbit");
    writeFile(dir + "/two.gltf", twoCameras());
    auto render = [&](const std::string& args) {
        CommandResult r = runGlint("two.gltf --size 9x9 -o c.png " + args, dir);
        EXPECT_EQ(r.exitCode, 0) << r.err;
        return readImage8(dir + "/c.png", 3);
    };
    auto blue = [](const Image8& img, int x, int y) {
        return img.at(x, y, 2) > img.at(x, y, 0) + 50;
    };
    // From +z, 5 away, around the blue quad's centre, then around the red one's; from +x
    // (theta 90) the quads are seen edge on, and the red one hides behind the blue.
    Image8 img = render("--camera orbit:0,90,5,3,0,0");
    EXPECT_TRUE(blue(img, 4, 4));
    EXPECT_FALSE(blue(img, 0, 0));  // 45 degrees: the quad, 2 wide, leaves the corners
    img = render("--camera orbit:0,90,5,-3,0,0");
    EXPECT_GT(img.at(4, 4, 0), img.at(4, 4, 2) + 50);
    // A narrow field of view fills the frame with the quad.
    img = render("--camera orbit:0,90,5,3,0,0 --fov 10");
    EXPECT_TRUE(blue(img, 0, 0));
    EXPECT_TRUE(blue(img, 8, 8));
    // It says whose camera it is.
    CommandResult r = runGlint("two.gltf --size 9x9 -o c.png --camera orbit:30,60,4.75", dir);
    EXPECT_TRUE(contains(r.err,
                         "(and the orbit camera theta 30, phi 60, radius 4.75 around (0, "
                         "0, 0))"))
        << r.err;
    // A scene file takes an orbit too, in place of its camera.
    writeFile(dir + "/s.test",
              "size 9 9\ncamera 0 0 50 0 0 0 0 1 0 1\nambient 0 0 0\ndirectional 0 0 1 1 1 1\n"
              "diffuse 1 1 1\nsphere 0 0 0 1\n");
    r = runGlint("s.test -o far.png", dir);  // a 1-degree view of the centre: all white
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_GT(readImage8(dir + "/far.png", 3).at(0, 0, 0), 200);
    r = runGlint("s.test -o orbit.png --camera orbit:0,90,10", dir);  // 45 degrees: black corners
    ASSERT_EQ(r.exitCode, 0) << r.err;
    Image8 orbit = readImage8(dir + "/orbit.png", 3);
    EXPECT_EQ(orbit.at(0, 0, 0), 0);
    EXPECT_GT(orbit.at(4, 4, 0), 200);
}

/// Two quads whose materials use KHR_materials_clearcoat and KHR_materials_pbrSpecularGlossiness
/// (which Glint ignores), one with KHR_materials_volume.
std::string coatedQuads() {
    GltfAsset a;
    int left = a.floats({-4, -1, 0, -2, -1, 0, -2, 1, 0, -4, 1, 0}, "VEC3");
    int right = a.floats({2, -1, 0, 4, -1, 0, 4, 1, 0, 2, 1, 0}, "VEC3");
    int indices = a.integers({0, 1, 2, 0, 2, 3}, GltfAsset::kUbyte, "SCALAR");
    auto quad = [&](int positions, int material) {
        return R"({"primitives": [{"attributes": {"POSITION": )" + std::to_string(positions) +
               R"(}, "indices": )" + std::to_string(indices) + R"(, "material": )" +
               std::to_string(material) + "}]}";
    };
    return a.text(R"("meshes": [)" + quad(left, 0) + ", " + quad(right, 1) + R"(],
        "extensionsUsed": ["KHR_materials_clearcoat", "KHR_materials_pbrSpecularGlossiness",
                           "KHR_materials_volume", "KHR_texture_transform"],
        "materials": [
          {"extensions": {"KHR_materials_clearcoat": {"clearcoatFactor": 1},
                          "KHR_materials_pbrSpecularGlossiness": {}}},
          {"pbrMetallicRoughness": {"baseColorFactor": [0, 0, 1, 1]},
           "extensions": {"KHR_materials_pbrSpecularGlossiness": {},
                          "KHR_materials_volume": {"thicknessFactor": 0}}}],
        "nodes": [{"mesh": 0}, {"mesh": 1}])");
}

/// How often `needle` occurs in `text`.
size_t occurrences(const std::string& text, const std::string& needle) {
    size_t n = 0;
    for (size_t at = text.find(needle); at != std::string::npos; at = text.find(needle, at + 1))
        ++n;
    return n;
}

TEST(CliGltf, CheckListsTheExtensionsUsedAndARenderWarnsOnceOfEachIgnoredOne) {
    std::string dir = freshDir("gltf-extensions");
    writeFile(dir + "/coated.gltf", coatedQuads());
    CommandResult r = runGlint("coated.gltf --check", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(contains(r.out, "coated.gltf: ok: ")) << r.out;
    EXPECT_TRUE(contains(r.out, "extensions used (4):\n")) << r.out;
    EXPECT_TRUE(contains(r.out,
                         "  KHR_materials_pbrSpecularGlossiness  ignored: specular-glossiness "
                         "materials are shaded by their metallic-roughness factors"))
        << r.out;
    EXPECT_TRUE(contains(r.out, "  KHR_materials_clearcoat              rendered\n")) << r.out;
    EXPECT_TRUE(contains(r.out, "  KHR_materials_volume                 rendered\n")) << r.out;
    EXPECT_TRUE(contains(r.out, "  KHR_texture_transform                rendered\n")) << r.out;

    // A render says it once, although two materials use it; nothing of the others.
    r = runGlint("coated.gltf --size 32x24 --spp 1", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(occurrences(r.err, "KHR_materials_pbrSpecularGlossiness"), 1u) << r.err;
    EXPECT_TRUE(
        contains(r.err,
                 "coated.gltf: warning: the file uses KHR_materials_pbrSpecularGlossiness, which "
                 "Glint does not render: specular-glossiness materials"))
        << r.err;
    EXPECT_EQ(occurrences(r.err, "KHR_materials_clearcoat"), 0u) << r.err;
    EXPECT_EQ(occurrences(r.err, "KHR_texture_transform"), 0u) << r.err;
    EXPECT_EQ(occurrences(r.err, "KHR_materials_volume"), 0u) << r.err;
    // Quiet renders too: it is a warning.
    r = runGlint("-q coated.gltf --size 32x24 --spp 1 -o q.png", dir);
    EXPECT_EQ(occurrences(r.err, "KHR_materials_pbrSpecularGlossiness"), 1u) << r.err;
    // A file without extensions lists none.
    writeFile(dir + "/two.gltf", twoCameras());
    r = runGlint("two.gltf --check", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_FALSE(contains(r.out, "extensions")) << r.out;
}

// KHR_materials_unlit (tests/data/gltf/unlit.gltf): a sign showing its texture as it is, to both
// integrators and whatever lights the scene, and casting no shadow on the floor it stands on.
TEST(CliGltf, AnUnlitSignShowsItsColoursAsTheyAreAndCastsNoShadow) {
    std::string dir = freshDir("gltf-unlit");
    const std::string text =
        readBytes(std::string(GLINT_SOURCE_DIR) + "/tests/data/gltf/unlit.gltf");
    writeFile(dir + "/unlit.gltf", text);
    std::string lit = text;  // the same file with the extension unknown: shaded and lit
    for (size_t at; (at = lit.find("KHR_materials_unlit")) != std::string::npos;)
        lit.replace(at, 19, "EXT_unknown_unlit");
    writeFile(dir + "/lit.gltf", lit);
    CommandResult r = runGlint("unlit.gltf --check", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(contains(r.out, "KHR_materials_unlit  rendered\n")) << r.out;

    const std::string small = " -q --size 64x48 --spp 4 --no-denoise";
    for (const char* run : {"unlit.gltf -o path.pfm", "unlit.gltf -o dark.pfm --environment none",
                            "unlit.gltf -o whitted.pfm --integrator whitted",
                            "lit.gltf -o lit.pfm --integrator whitted"}) {
        r = runGlint(run + small, dir);
        ASSERT_EQ(r.exitCode, 0) << run << "\n" << r.err;
    }
    const Film path = readPfm(dir + "/path.pfm"), dark = readPfm(dir + "/dark.pfm"),
               whitted = readPfm(dir + "/whitted.pfm"), shaded = readPfm(dir + "/lit.pfm");
    // A pixel of the sign's orange: the same colour without the studio's light and to the
    // Whitted integrator; shaded, it is another.
    const Vec3 sign = path.at(32, 22);
    EXPECT_GT(sign.x, 0.5) << sign;
    EXPECT_LT(sign.z, 0.1) << sign;
    EXPECT_NEAR(length(dark.at(32, 22) - sign), 0, 1e-6) << dark.at(32, 22);
    EXPECT_NEAR(length(whitted.at(32, 22) - sign), 0, 1e-6) << whitted.at(32, 22);
    EXPECT_GT(length(shaded.at(32, 22) - sign), 0.1) << shaded.at(32, 22);
    // The floor where a lit sign casts its shadow: lit by the sun when the sign is unlit.
    EXPECT_GT(whitted.at(28, 40).x, 2 * shaded.at(28, 40).x)
        << whitted.at(28, 40) << " " << shaded.at(28, 40);
}

// A file lit in physical units (tests/data/gltf/lamp-in-lux.gltf: a 1500 cd bulb and a 512 lux
// sun): the model mode chooses an exposure and says so, --exposure overrides it, and the bulb
// around the point light leaves no dark halo on the ground shadow (issue 37).
TEST(CliGltf, LightsInPhysicalUnitsGetAnExposureAndTheirBulbNoHalo) {
    std::string dir = freshDir("gltf-lux");
    writeFile(dir + "/lamp.gltf",
              readBytes(std::string(GLINT_SOURCE_DIR) + "/tests/data/gltf/lamp-in-lux.gltf"));
    const std::string small = " --size 64x48 --spp 16 --no-denoise";
    CommandResult r = runGlint("lamp.gltf -o chosen.pfm" + small, dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(contains(r.err,
                         "its lights are in physical units (candela, lux), 256 times as "
                         "bright as the studio: exposure -8 (--exposure changes it)"))
        << r.err;
    r = runGlint("lamp.gltf -o raw.pfm --exposure 0" + small, dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const Film chosen = readPfm(dir + "/chosen.pfm"), raw = readPfm(dir + "/raw.pfm");
    for (auto [x, y] : {std::pair{10, 10}, {32, 30}, {46, 32}})
        EXPECT_NEAR(chosen.at(x, y).y * 256, raw.at(x, y).y, 1e-4 * raw.at(x, y).y)
            << x << " " << y;
    // The ground beside the bulb shows the studio as it is (about 0.49), not a shadow.
    EXPECT_GT(raw.at(46, 32).y, 0.45) << raw.at(46, 32);
}

}  // namespace
}  // namespace glint::test
