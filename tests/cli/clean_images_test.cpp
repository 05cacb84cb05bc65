// Clean images from the command line (docs/clean-images.md): render passes as EXR layers,
// --denoise, glint denoise, adaptive sampling and the model mode's defaults.

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "cli/cli_support.h"
#include "glint/io/image/image_io.h"

namespace glint::test {
namespace {

namespace fs = std::filesystem;

/// A path-traced course scene: a diffuse sphere on a checkered floor under a sky.
const char* kScene =
    "size 40 30\nintegrator path\ncamera 0 1 4 0 0.5 0 0 1 0 45\nbackground 0.6 0.7 1\n"
    "ambient 0 0 0\ndiffuse 0.8 0.8 0.8\nchecker 0.8 0.8 0.8 0.2 0.2 0.2 0.5\n"
    "plane 0 0 0 0 1 0\ntexture none\ndiffuse 0.7 0.3 0.2\nsphere 0 0.6 0 0.6\n";

std::string withScene(const std::string& name) {
    const std::string dir = freshDir(name);
    writeFile(dir + "/s.test", kScene);
    return dir;
}

TEST(CliCleanImages, AovsAreLayersOfTheExrOutput) {
    const std::string dir = withScene("clean-aov");
    CommandResult r = runGlint("-q s.test --spp 4 --aov albedo,depth -o out.exr", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const ExrLayers l = readExrLayers(dir + "/out.exr");
    EXPECT_TRUE(l.found.albedo && l.found.depth);
    EXPECT_FALSE(l.found.normal || l.found.variance);
    // The sphere's red albedo in the middle of the image; the beauty is the same as without
    // passes.
    EXPECT_NEAR(l.aovs.albedo[l.aovs.index(20, 12)].x, 0.7, 1e-6);
    r = runGlint("-q s.test --spp 4 -o plain.exr", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const Film plain = readExr(dir + "/plain.exr");
    EXPECT_EQ(plain.at(20, 12), l.color.at(20, 12));
    r = runGlint("-q s.test --spp 4 --aov all -o all.exr", dir);
    EXPECT_TRUE(readExrLayers(dir + "/all.exr").found.variance);
}

TEST(CliCleanImages, AovsNeedAnExrFileAndKnownNames) {
    const std::string dir = withScene("clean-aov-errors");
    CommandResult r = runGlint("s.test --aov albedo -o out.png", dir);
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_TRUE(contains(r.err, "--aov writes the passes as layers of an OpenEXR file")) << r.err;
    r = runGlint("s.test --aov albedo,shadow -o out.exr", dir);
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_TRUE(contains(r.err, "unknown pass 'shadow'")) << r.err;
}

TEST(CliCleanImages, DenoiseSmoothsAndGlintDenoiseDoesTheSameToASavedRender) {
    const std::string dir = withScene("clean-denoise");
    CommandResult r = runGlint("-q s.test --spp 8 --aov all -o raw.exr", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    r = runGlint("-q s.test --spp 8 --denoise --aov all -o denoised.exr", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    r = runGlint("denoise -q raw.exr -o later.exr", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const Film raw = readExr(dir + "/raw.exr"), now = readExr(dir + "/denoised.exr"),
               later = readExr(dir + "/later.exr");
    // The same denoiser on the same buffers (the EXR's floats: within float rounding).
    double differs = 0, change = 0;
    for (int y = 0; y < 30; ++y)
        for (int x = 0; x < 40; ++x) {
            differs = std::max(differs, std::abs(now.at(x, y).x - later.at(x, y).x));
            change += std::abs(raw.at(x, y).x - now.at(x, y).x);
        }
    EXPECT_LT(differs, 1e-3);
    EXPECT_GT(change, 0);  // it did something
    // The passes come along into the denoised file.
    EXPECT_TRUE(readExrLayers(dir + "/later.exr").found.albedo);
    // A PNG too, and errors as usual.
    r = runGlint("denoise -q raw.exr -o later.png --tonemap neutral --srgb", dir);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    r = runGlint("denoise missing.exr -o x.png", dir);
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_TRUE(contains(r.err, "glint denoise: error: cannot read image 'missing.exr'")) << r.err;
    r = runGlint("denoise raw.exr", dir);
    EXPECT_EQ(r.exitCode, 2);
    // Not an OpenEXR file: what it reads, and how to make one.
    r = runGlint("denoise later.png -o again.png", dir);
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_EQ(r.err,
              "glint denoise: error: later.png is not an OpenEXR file: glint denoise reads "
              "renders saved as OpenEXR, with their passes (glint SCENE -o render.exr --aov "
              "all)\n");
}

TEST(CliCleanImages, AdaptiveSamplingSaysWhatItDid) {
    const std::string dir = withScene("clean-adaptive");
    CommandResult r = runGlint("s.test --noise-threshold 0.05 --min-spp 8 --spp 64 -o a.png", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(contains(r.err, "glint: adaptive sampling: ")) << r.err;
    EXPECT_TRUE(contains(r.err, "below noise 0.05")) << r.err;
    // The same command, the same bytes (no time budget: reproducible).
    r = runGlint("-q s.test --noise-threshold 0.05 --min-spp 8 --spp 64 -o b.png -t 1", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(readBytes(dir + "/a.png"), readBytes(dir + "/b.png"));
    r = runGlint("s.test --noise-threshold 2", dir);
    EXPECT_EQ(r.exitCode, 2);
    r = runGlint("s.test --noise-threshold 0.1 --samples 0:8 -o p.exr", dir);
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_TRUE(contains(r.err, "split the frame into pieces with --part or --crop")) << r.err;
    r = runGlint("s.test --denoise --part 0/2 -o p.exr", dir);
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_TRUE(contains(r.err, "denoise the merged image")) << r.err;
}

TEST(CliCleanImages, AdaptivePiecesWithPassesMergeToTheWholeRendersBytes) {
    // Each pixel stops on its own samples: pieces split by rows and crops make the same pixels
    // and passes, which the merge writes as the single render does; glint denoise then takes
    // the merged file.
    const std::string dir = withScene("clean-adaptive-pieces");
    const std::string common = "-q s.test --noise-threshold 0.05 --min-spp 4 --spp 64 --aov all";
    CommandResult r = runGlint(common + " -o whole.exr", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    for (const char* piece :
         {"--crop 0,40,0,16 --part 0/2 -o a.exr", "--crop 0,40,0,16 --part 1/2 -o b.exr",
          "--crop 0,40,16,30 -o c.exr"}) {
        r = runGlint(common + " -t 1 " + piece, dir);
        ASSERT_EQ(r.exitCode, 0) << piece << ": " << r.err;
    }
    r = runGlint("merge -q -o merged.exr c.exr b.exr a.exr", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(readBytes(dir + "/merged.exr"), readBytes(dir + "/whole.exr"));
    EXPECT_TRUE(readExrLayers(dir + "/merged.exr").found.variance);
    r = runGlint("denoise -q merged.exr -o clean.png", dir);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    // An 8-bit merge has no layers: said, and the image written.
    r = runGlint("merge -o merged.png a.exr b.exr c.exr", dir);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(contains(r.err, "only an .exr output holds")) << r.err;
    // Pieces with other passes, or without adaptive sampling, are not of one frame.
    r = runGlint(
        "-q s.test --noise-threshold 0.05 --min-spp 4 --spp 64 --aov albedo -t 1 "
        "--crop 0,40,16,30 -o d.exr",
        dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    r = runGlint("merge -o m.exr a.exr b.exr d.exr", dir);
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_TRUE(contains(r.err, "passes albedo, but a.exr has passes albedo,normal,depth,variance"))
        << r.err;
}

TEST(CliCleanImages, ClampIndirectDarkensTheIndirectLightAndIsNamedInPieces) {
    const std::string dir = withScene("clean-clamp");
    CommandResult r = runGlint("-q s.test --spp 16 -o full.pfm", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    r = runGlint("-q s.test --spp 16 --clamp-indirect 0.01 -o clamped.pfm", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const Film full = readPfm(dir + "/full.pfm"), clamped = readPfm(dir + "/clamped.pfm");
    double a = 0, b = 0;
    for (int y = 0; y < 30; ++y)
        for (int x = 0; x < 40; ++x) {
            a += full.at(x, y).x;
            b += clamped.at(x, y).x;
            EXPECT_LE(clamped.at(x, y).x, full.at(x, y).x + 1e-9) << x << "," << y;
        }
    EXPECT_LT(b, a);
    // Pieces of other clamps are not of one frame; the Whitted integrator says it ignores it.
    r = runGlint("-q s.test --spp 4 --clamp-indirect 0.5 --part 0/2 -o p0.exr", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    r = runGlint("-q s.test --spp 4 --part 1/2 -o p1.exr", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    r = runGlint("merge -o m.png p0.exr p1.exr", dir);
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_TRUE(contains(r.err, "clamp-indirect")) << r.err;
    r = runGlint("s.test --integrator whitted --clamp-indirect 1 -o w.png", dir);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(contains(r.err, "--clamp-indirect applies to the path tracer")) << r.err;
}

TEST(CliCleanImages, ModelsAreSampledUntilCleanAndDenoisedByDefault) {
    const std::string dir = freshDir("clean-model");
    fs::copy_file(std::string(GLINT_TEST_DATA_DIR) + "/meshes/flat.obj", dir + "/flat.obj");
    CommandResult r = runGlint("flat.obj --size 24x18 -o m.png", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(contains(r.err, "glint: adaptive sampling (a model's default): ")) << r.err;
    EXPECT_TRUE(contains(r.err, "glint: denoised in ")) << r.err;
    // A fixed sample count or --no-denoise turns each off.
    r = runGlint("flat.obj --size 24x18 --spp 4 --no-denoise -o n.png", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_FALSE(contains(r.err, "adaptive")) << r.err;
    EXPECT_FALSE(contains(r.err, "denoised")) << r.err;
    // Scenes are never denoised unless asked.
    writeFile(dir + "/s.test", kScene);
    r = runGlint("s.test --spp 4 -o s.png", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_FALSE(contains(r.err, "denoised")) << r.err;
}

}  // namespace
}  // namespace glint::test
