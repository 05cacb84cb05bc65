// Frame pieces as a farm renders them: glint --part, --crop and --samples write OpenEXR
// pieces, glint merge checks and adds them. Pieces give the single render's bytes in every
// format, whether they split the pixels or their samples. Errors name the option, the file,
// and what is missing or doubled.

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "cli/cli_support.h"
#include "glint/io/image/image_io.h"

namespace glint::test {
namespace {

namespace fs = std::filesystem;

/// A path-traced scene with several samples: an area light, a glossy floor through a lens, a
/// mesh (so that the scene hash covers a second file), 24 x 52 pixels (4 rows of 16-pixel
/// tiles, the last 4 pixels high).
const char* const kPathScene =
    "size 24 52\n"
    "integrator path\nspp 8\nmaxdepth 4\n"
    "camera 0 1 5 0 0.5 0 0 1 0 40\n"
    "lens 0.05 5\n"
    "quadLight -0.5 2.5 -0.5 1 0 0 0 0 1 6 6 6\n"
    "diffuse 0.6 0.6 0.6\nspecular 0.2 0.2 0.2\nshininess 20\n"
    "vertex -3 0 -3\nvertex 3 0 -3\nvertex 3 0 3\nvertex -3 0 3\ntri 0 2 1\ntri 0 3 2\n"
    "specular 0 0 0\ndiffuse 0.8 0.3 0.2\nsphere -0.7 0.5 0 0.5\n"
    "diffuse 0.2 0.5 0.8\nmesh tetra.obj\n";

const char* const kTetrahedron =
    "v 0.3 0 -0.2\nv 1.3 0 -0.2\nv 0.3 1 -0.2\nv 0.3 0 0.8\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";

std::string pathSceneDir(const std::string& name) {
    std::string dir = freshDir(name);
    writeFile(dir + "/scene.test", kPathScene);
    writeFile(dir + "/tetra.obj", kTetrahedron);
    return dir;
}

/// A course scene (Whitted, one sample), at a small size.
const std::string kCourseScene = std::string(GLINT_TEST_DATA_DIR) + "/cse167x/scene4-specular.test";

/// A course scene of flat colours (ambient light only).
const std::string kAmbientScene = std::string(GLINT_TEST_DATA_DIR) + "/cse167x/scene4-ambient.test";

/// Runs glint and expects success.
void glint(const std::string& args, const std::string& dir) {
    CommandResult r = runGlint("-q " + args, dir);
    ASSERT_EQ(r.exitCode, 0) << args << ": " << r.err;
}

/// Runs glint merge and expects success.
void merge(const std::string& args, const std::string& dir) {
    CommandResult r = runGlint("merge -q " + args, dir);
    ASSERT_EQ(r.exitCode, 0) << args << ": " << r.err;
    EXPECT_EQ(r.err, "");
}

/// Renders `scene` whole and as `pieces` (each the piece options of one run), merges them to
/// merged.{png,exr,pfm}, and expects the whole render's bytes in each.
void renderAndMerge(const std::string& dir, const std::string& scene,
                    const std::vector<std::string>& pieces) {
    for (const char* ext : {"png", "exr", "pfm"}) glint(scene + " -o whole." + ext, dir);
    std::string names;
    for (size_t i = 0; i < pieces.size(); ++i) {
        std::string name = "piece" + std::to_string(i) + ".exr";
        glint(scene + " " + pieces[i] + " -t 1 -o " + name, dir);
        names = name + " " + names;  // named in reverse: the order must not matter
    }
    for (const char* ext : {"png", "exr", "pfm"}) {
        CommandResult r = runGlint(std::string("merge -o merged.") + ext + " " + names, dir);
        ASSERT_EQ(r.exitCode, 0) << r.err;
        EXPECT_TRUE(contains(r.err, "glint merge: wrote merged.")) << r.err;
    }
    for (const char* ext : {"png", "exr", "pfm"})
        EXPECT_TRUE(readBytes(dir + "/merged." + ext) == readBytes(dir + "/whole." + ext))
            << scene << ": merged." << ext << " is not whole." << ext << ", byte for byte";
}

TEST(CliPieces, FourPartsMergeToTheSameBytes) {
    std::string dir = pathSceneDir("pieces-parts");
    renderAndMerge(dir, "scene.test", {"--part 0/4", "--part 1/4", "--part 2/4", "--part 3/4"});
    // 52 rows in 4 parts: bands of 52 / 4 = 13 rows (thinner than a 16-pixel tile, so that
    // every part holds pixels and they hold as many); part 3/4 is rows 39-51.
    CommandResult r = runGlint("scene.test --part 3/4 -o p3.exr", dir);
    EXPECT_TRUE(contains(r.err, "glint: wrote p3.exr (part 3/4 of the 24x52 frame: 312 pixels)"))
        << r.err;
    // 3 parts keep 16-row bands (52 / 3 > 16): part 0/3 is rows 0-15 and 48-51.
    r = runGlint("scene.test --part 0/3 -o p0.exr", dir);
    EXPECT_TRUE(contains(r.err, "glint: wrote p0.exr (part 0/3 of the 24x52 frame: 480 pixels)"))
        << r.err;
}

TEST(CliPieces, ThreeCropsOfACourseSceneMergeToTheSameBytes) {
    std::string dir = freshDir("pieces-crops");
    renderAndMerge(dir, "'" + kCourseScene + "' --size 40x30",
                   {"--crop 0,17,0,30", "--crop 17,40,0,11", "--crop 17,40,11,30"});
}

TEST(CliPieces, SampleRangesMergeToTheSameBytes) {
    std::string dir = pathSceneDir("pieces-samples");
    renderAndMerge(dir, "scene.test", {"--samples 0:3", "--samples 3:8"});
    renderAndMerge(dir, "scene.test", {"--samples 0:1", "--samples 1:6", "--samples 6:8"});
}

TEST(CliPieces, SampleRangesOfACourseSceneMergeToTheSameBytes) {
    // Flat colours that sit on an 8-bit level's edge (ambient 0.4: 255 x 0.4 = 102): a pixel's
    // average must be the single render's to the last bit, or floor(255 c) drops a level. With
    // 6 and 10 samples (1/n inexact), sums added in another order did in 4% of the pixels.
    std::string dir = freshDir("pieces-samples-course");
    const std::string scene = "'" + kAmbientScene + "' --size 80x60 --spp ";
    renderAndMerge(dir, scene + "6", {"--samples 0:2", "--samples 2:6"});
    renderAndMerge(dir, scene + "10", {"--samples 0:3", "--samples 3:4", "--samples 4:10"});
}

TEST(CliPieces, PartsCropsAndSamplesCombine) {
    std::string dir = pathSceneDir("pieces-mixed");
    renderAndMerge(dir, "scene.test",
                   {"--crop 0,24,0,32 --part 0/2", "--crop 0,24,0,32 --part 1/2 --samples 0:5",
                    "--crop 0,24,0,32 --part 1/2 --samples 5:8", "--crop 0,24,32,52"});
}

TEST(CliPieces, AModelsPiecesMergeWithItsDisplay) {
    // The model mode writes through PBR Neutral and sRGB: the pieces record it for the merge.
    // (Pieces are raw sums: the whole render is compared undenoised.)
    std::string dir = freshDir("pieces-model");
    fs::copy_file(std::string(GLINT_TEST_DATA_DIR) + "/meshes/flat.obj", dir + "/flat.obj");
    glint("flat.obj --size 20x18 --spp 2 --no-denoise -o whole.png", dir);
    glint("flat.obj --size 20x18 --spp 2 --part 0/2 -o a.exr", dir);
    glint("flat.obj --size 20x18 --spp 2 --part 1/2 -o b.exr", dir);
    merge("a.exr b.exr -o merged.png", dir);
    EXPECT_EQ(readBytes(dir + "/merged.png"), readBytes(dir + "/whole.png"));
    // And the merge's own display options win.
    glint("flat.obj --size 20x18 --spp 2 --no-denoise --no-srgb --tonemap clamp -o plain.png", dir);
    merge("a.exr b.exr --no-srgb --tonemap clamp -o plain-merged.png", dir);
    EXPECT_EQ(readBytes(dir + "/plain-merged.png"), readBytes(dir + "/plain.png"));
    EXPECT_NE(readBytes(dir + "/plain.png"), readBytes(dir + "/whole.png"));
}

TEST(CliPieces, BadPieceOptionsAreUsageErrors) {
    std::string dir = pathSceneDir("pieces-usage");
    auto usage = [&](const std::string& args, const std::string& message) {
        CommandResult r = runGlint("scene.test " + args, dir);
        EXPECT_EQ(r.exitCode, 2) << args << ": " << r.err;
        EXPECT_TRUE(contains(r.err, message)) << args << ": " << r.err;
    };
    usage("--part 4/4 -o a.exr", "K must be 0 to N-1");
    usage("--part 1/0 -o a.exr", "N must be 1 to 65536");
    usage("--part 2 -o a.exr", "expected K/N");
    usage("--part 52/53 -o a.exr",
          "--part 52/53: the image is 52 pixels high, so N may be at most 52");
    usage("--crop 0,24,0,10 --part 1/11 -o a.exr",
          "--part 1/11: the crop is 10 pixels high, so N may be at most 10");
    usage("--crop 0,10,0 -o a.exr", "expected x0,x1,y0,y1");
    usage("--crop 5,5,0,4 -o a.exr", "is empty");
    usage("--crop 0,25,0,20 -o a.exr",
          "--crop 0,25,0,20 reaches beyond the 24x52 image: x1 may be at most 24 and y1 at most "
          "52");
    usage("--samples 0:9 -o a.exr", "the frame has 8 samples per pixel, so B may be at most 8");
    usage("--samples 3:3 -o a.exr", "A < B");
    usage("--part 0/2 -o a.png", "'a.png' is not an .exr file");
    usage("--part 0/2", "name its OpenEXR file with -o FILE.exr");
    usage("--part 0/2 --time 1 -o a.exr", "not --time");
    usage("--samples 0:4 --noise-threshold 0.1 -o a.exr", "split the frame into pieces with");
    EXPECT_FALSE(fs::exists(dir + "/a.exr"));
    EXPECT_FALSE(fs::exists(dir + "/a.png"));
}

TEST(CliPieces, MergeNamesWhatIsMissingDoubledOrForeign) {
    std::string dir = pathSceneDir("pieces-merge-errors");
    for (int k = 0; k < 2; ++k)
        glint("scene.test --part " + std::to_string(k) + "/2 -o p" + std::to_string(k) + ".exr",
              dir);
    glint("scene.test --part 1/2 -o again.exr", dir);
    glint("scene.test --part 1/2 --seed 3 -o seed3.exr", dir);
    glint("scene.test --part 1/2 --maxdepth 2 -o depth2.exr", dir);
    glint("scene.test -o image.exr", dir);
    auto fails = [&](const std::string& args, const std::string& message) {
        CommandResult r = runGlint("merge -o out.png " + args, dir);
        EXPECT_EQ(r.exitCode, 1) << args << ": " << r.err;
        EXPECT_TRUE(contains(r.err, message)) << args << ": " << r.err;
        EXPECT_FALSE(fs::exists(dir + "/out.png"));
    };
    fails("p0.exr",
          "glint merge: error: part 1/2 is missing: no piece covers samples 0:8 of its 480 pixels");
    fails("p0.exr p1.exr again.exr",
          "again.exr: error: part 1/2 given twice: p1.exr and again.exr");
    fails("p0.exr seed3.exr", "seed3.exr: error: seed 3, but p0.exr has seed 0");
    fails("p0.exr depth2.exr", "depth2.exr: error: maxdepth=2, but p0.exr has maxdepth=4");
    fails("p0.exr image.exr", "image.exr: error: not a Glint frame piece");
    fails("p0.exr none.exr", "none.exr: error: cannot read it");
    // Truncated: a clear error, never a crash.
    std::string bytes = readBytes(dir + "/p1.exr");
    writeFile(dir + "/cut.exr", bytes.substr(0, bytes.size() / 2));
    fails("p0.exr cut.exr", "cut.exr: error: ");

    // Another version of the mesh: the scene hash tells the pieces apart.
    writeFile(dir + "/tetra.obj", std::string(kTetrahedron) + "v 0 0 0\n");
    glint("scene.test --part 1/2 -o newmesh.exr", dir);
    fails("p0.exr newmesh.exr", "newmesh.exr: error: scene hash ");

    CommandResult r = runGlint("merge p0.exr p1.exr", dir);
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_TRUE(contains(r.err, "--output is required")) << r.err;
    r = runGlint("merge -o out.tga p0.exr p1.exr", dir);
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_TRUE(contains(r.err, "unknown image format")) << r.err;
    r = runGlint("merge --help", dir);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(contains(r.out, "glint merge")) << r.out;
}

TEST(CliPieces, TheDemosPiecesMerge) {
    std::string dir = freshDir("pieces-demo");
    glint("--size 32x24 -o whole.png", dir);
    glint("--size 32x24 --crop 0,32,0,10 -o a.exr", dir);
    glint("--size 32x24 --crop 0,32,10,24 -o b.exr", dir);
    merge("a.exr b.exr -o merged.png", dir);
    EXPECT_EQ(readBytes(dir + "/merged.png"), readBytes(dir + "/whole.png"));
}

}  // namespace
}  // namespace glint::test
