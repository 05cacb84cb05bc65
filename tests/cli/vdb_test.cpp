// A medium whose density is an OpenVDB grid, through the glint program: the program links no
// OpenVDB library (layering.no_openvdb_in_glint) and loads its OpenVDB module the first time a
// .vdb file is read (io/vdb/vdb_module.h). The grid is the fuzzer's seed tiny.vdb: three voxels
// of 0.25 (densities 1, 0.5 and 2), the first about the origin.

#include <gtest/gtest.h>

#include <string>

#include "cli/cli_support.h"
#include "glint/io/image/exr.h"
#include "glint/io/image/image_io.h"

namespace glint::test {
namespace {

TEST(CliVdb, AMediumFromAVdbFileAbsorbsWhereItsGridIsDense) {
    const std::string dir = freshDir("vdb");
    writeFile(dir + "/tiny.vdb", readBytes(std::string(GLINT_FUZZ_DIR) + "/corpus/vdb/tiny.vdb"));
    // A white sky seen through the grid, which absorbs strongly: dark where the camera looks
    // through the voxel at the origin, white far beside it.
    writeFile(dir + "/scene.test",
              "size 9 9\nintegrator path\nspp 4\ncamera 0 0 3 0 0 0 0 1 0 20\n"
              "background 1 1 1 1 1 1\n"
              "medium grid absorption 40 40 40 scattering 0 0 0 density tiny.vdb\nfog grid\n");
    const CommandResult r = runGlint("-q -t 1 scene.test -o out.exr", dir);
#if GLINT_HAVE_OPENVDB
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(r.err, "");
    const Film out = readExr(dir + "/out.exr");
    EXPECT_LT(out.at(4, 4).y, 0.05);  // through the voxel of density 1: e^-10
    EXPECT_GT(out.at(0, 0).y, 0.99);  // beside the grid: the sky
#else
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_TRUE(contains(r.err, "scene.test:6:")) << r.err;
    EXPECT_TRUE(contains(r.err, "reads no OpenVDB files")) << r.err;
#endif
}

}  // namespace
}  // namespace glint::test
