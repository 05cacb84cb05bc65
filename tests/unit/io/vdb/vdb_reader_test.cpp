// OpenVDB density grids (io/vdb/vdb_reader.h): small .vdb files written here with OpenVDB
// itself, read back as DensityGrids (values, placement, which grid), and the files that must be
// refused with a message. Without OpenVDB (GLINT_OPENVDB=OFF) only the refusal is tested.

#include "glint/io/vdb/vdb_reader.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

#include "glint/core/error.h"
#include "glint/render/renderer.h"
#include "unit/test_support.h"

#if GLINT_HAVE_OPENVDB
#include <openvdb/io/File.h>
#include <openvdb/io/Stream.h>
#include <openvdb/openvdb.h>
#include <tbb/task_arena.h>
#endif

namespace glint {
namespace {

using ::testing::HasSubstr;

/// The message loadVdbDensity throws for `path` (and grid), or "" if it loads.
std::string loadError(const std::string& path, const std::string& grid = "",
                      const LoadLimits& limits = {}) {
    try {
        loadVdbDensity(path, grid, limits);
    } catch (const RenderError& e) {
        return e.what();
    }
    return "";
}

#if !GLINT_HAVE_OPENVDB

TEST(VdbReaderNone, RefusesEveryFile) {
    EXPECT_THAT(loadError("smoke.vdb"), HasSubstr("this build of Glint reads no OpenVDB files"));
    EXPECT_THAT(loadError("smoke.vdb"), HasSubstr("smoke.vdb"));
}

#else

using openvdb::Coord;
using openvdb::FloatGrid;

class VdbReaderTest : public test::TempDirTest {
  protected:
    void SetUp() override {
        TempDirTest::SetUp();
        openvdb::initialize();
    }

    /// `grids` written to `name` in the test's directory; `stats` false leaves out the
    /// metadata (active box, memory) the reader checks before reading voxels.
    std::string write(const std::string& name, const openvdb::GridPtrVec& grids,
                      bool stats = true) {
        const std::string p = path(name);
        openvdb::io::File file(p);
        file.setGridStatsMetadataEnabled(stats);
        // In a one-slot arena, as the reader does: no TBB threads in the test process, whose
        // other tests count threads.
        tbb::task_arena(1).execute([&] { file.write(grids); });
        file.close();
        return p;
    }

    static FloatGrid::Ptr floatGrid(const std::string& name, float background = 0) {
        FloatGrid::Ptr grid = FloatGrid::create(background);
        grid->setName(name);
        return grid;
    }
};

/// The dense grid's density at the world position of the OpenVDB voxel `c` of `grid` (its
/// centre), found as a renderer would: world to index space by worldFromIndex's inverse.
double densityAtVoxel(const DensityGrid& dense, const openvdb::GridBase& grid, const Coord& c) {
    const openvdb::Vec3d w = grid.indexToWorld(c);
    return dense.lookup(dense.worldFromIndex.inversePoint({w.x(), w.y(), w.z()}));
}

TEST_F(VdbReaderTest, ValuesAndPlacementRoundTrip) {
    FloatGrid::Ptr grid = floatGrid("density");
    grid->setTransform(openvdb::math::Transform::createLinearTransform(0.5));
    grid->transform().postTranslate(openvdb::Vec3d(1, 2, 3));
    auto acc = grid->getAccessor();
    acc.setValue(Coord(3, -2, 5), 2.5f);
    acc.setValue(Coord(6, 1, 7), 1.25f);
    auto dense = loadVdbDensity(write("one.vdb", {grid}), "", {});

    // The active box, (3, -2, 5) to (6, 1, 7), voxel for voxel.
    EXPECT_EQ(dense->nx, 4);
    EXPECT_EQ(dense->ny, 4);
    EXPECT_EQ(dense->nz, 3);
    EXPECT_EQ(dense->at(0, 0, 0), 2.5f);
    EXPECT_EQ(dense->at(3, 3, 2), 1.25f);
    EXPECT_EQ(dense->at(1, 1, 1), 0.0f);
    EXPECT_FLOAT_EQ(dense->maxDensity(), 2.5f);
    EXPECT_THAT(dense->name, HasSubstr("one.vdb"));
    EXPECT_THAT(dense->name, HasSubstr("density"));

    // At each voxel's world centre the density is its value; 0 at inactive voxels and outside.
    EXPECT_NEAR(densityAtVoxel(*dense, *grid, Coord(3, -2, 5)), 2.5, 1e-9);
    EXPECT_NEAR(densityAtVoxel(*dense, *grid, Coord(6, 1, 7)), 1.25, 1e-9);
    EXPECT_EQ(densityAtVoxel(*dense, *grid, Coord(5, 0, 6)), 0.0);
    EXPECT_EQ(densityAtVoxel(*dense, *grid, Coord(-20, 40, 9)), 0.0);
    EXPECT_EQ(densityAtVoxel(*dense, *grid, Coord(8, 1, 7)), 0.0);

    // Glint's voxel (0, 0, 0) covers OpenVDB's voxel (3, -2, 5): from index (2.5, -2.5, 4.5),
    // world 0.5 * that + (1, 2, 3), to (3.5, -1.5, 5.5).
    test::expectNear(dense->worldFromIndex.point({0, 0, 0}), {2.25, 0.75, 5.25}, 1e-12);
    test::expectNear(dense->worldFromIndex.point({1, 1, 1}), {2.75, 1.25, 5.75}, 1e-12);
}

TEST_F(VdbReaderTest, RotatedScaledTransformPlacesEveryVoxel) {
    // A rotation about z, a non-uniform scale and a translation (OpenVDB's row-vector order).
    openvdb::math::Transform::Ptr xf = openvdb::math::Transform::createLinearTransform(1.0);
    xf->preScale(openvdb::Vec3d(0.5, 2, 1.5));
    xf->postRotate(0.7, openvdb::math::Z_AXIS);
    xf->postRotate(-0.3, openvdb::math::X_AXIS);
    xf->postTranslate(openvdb::Vec3d(-4, 10, 0.25));
    ASSERT_TRUE(xf->isLinear());
    FloatGrid::Ptr grid = floatGrid("density");
    grid->setTransform(xf);
    auto acc = grid->getAccessor();
    for (int i = 0; i < 5; ++i) acc.setValue(Coord(i - 2, 3 * i, -i), 1.0f + static_cast<float>(i));
    auto dense = loadVdbDensity(write("rotated.vdb", {grid}), "", {});

    for (int i = 0; i < 5; ++i)
        EXPECT_NEAR(densityAtVoxel(*dense, *grid, Coord(i - 2, 3 * i, -i)), 1.0 + i, 1e-9) << i;
    // Halfway between two voxels of one row, in world space: the average of the two.
    FloatGrid::Ptr pair = floatGrid("density");
    pair->setTransform(xf);
    pair->getAccessor().setValue(Coord(0, 0, 0), 2.0f);
    pair->getAccessor().setValue(Coord(1, 0, 0), 4.0f);
    auto dense2 = loadVdbDensity(write("pair.vdb", {pair}), "", {});
    const openvdb::Vec3d mid = pair->indexToWorld(openvdb::Vec3d(0.5, 0, 0));
    EXPECT_NEAR(dense2->lookup(dense2->worldFromIndex.inversePoint({mid.x(), mid.y(), mid.z()})),
                3.0, 1e-9);
}

TEST_F(VdbReaderTest, TilesBackgroundAndNegativeValues) {
    // An active tile (8^3 voxels at the leaf level) and a voxel beyond it with a gap between:
    // the gap is inactive and reads as the background; a negative value becomes 0.
    FloatGrid::Ptr grid = floatGrid("density", 0.25f);
    grid->tree().addTile(1, Coord(0, 0, 0), 3.0f, true);
    grid->getAccessor().setValue(Coord(10, 0, 0), -1.0f);
    auto dense = loadVdbDensity(write("tile.vdb", {grid}), "", {});
    ASSERT_EQ(dense->nx, 11);
    ASSERT_EQ(dense->ny, 8);
    ASSERT_EQ(dense->nz, 8);
    EXPECT_EQ(dense->at(0, 0, 0), 3.0f);
    EXPECT_EQ(dense->at(7, 7, 7), 3.0f);
    EXPECT_EQ(dense->at(8, 0, 0), 0.25f);
    EXPECT_EQ(dense->at(10, 0, 0), 0.0f);
    EXPECT_EQ(dense->at(10, 7, 7), 0.25f);

    FloatGrid::Ptr negative = floatGrid("density", -2.0f);
    negative->getAccessor().setValue(Coord(0, 0, 0), 1.0f);
    negative->getAccessor().setValue(Coord(2, 0, 0), 1.0f);
    auto clamped = loadVdbDensity(write("negative.vdb", {negative}), "", {});
    EXPECT_EQ(clamped->at(1, 0, 0), 0.0f);
}

TEST_F(VdbReaderTest, NonFiniteValuesAreRefused) {
    FloatGrid::Ptr grid = floatGrid("density");
    grid->getAccessor().setValue(Coord(1, 2, 3), 1.0f);
    grid->getAccessor().setValue(Coord(4, 5, 6), std::numeric_limits<float>::quiet_NaN());
    const std::string message = loadError(write("nan.vdb", {grid}));
    EXPECT_THAT(message, HasSubstr("nan.vdb"));
    EXPECT_THAT(message, HasSubstr("voxel (4, 5, 6)"));
    EXPECT_THAT(message, HasSubstr("finite"));

    FloatGrid::Ptr inf = floatGrid("density");
    inf->tree().addTile(1, Coord(0, 0, 0), std::numeric_limits<float>::infinity(), true);
    EXPECT_THAT(loadError(write("inf.vdb", {inf})), HasSubstr("inf"));
}

TEST_F(VdbReaderTest, ChoosesTheNamedGridOrDensityOrTheFirstFloatGrid) {
    auto constant = [&](const std::string& name, float v) {
        FloatGrid::Ptr g = floatGrid(name);
        g->getAccessor().setValue(Coord(0, 0, 0), v);
        return g;
    };
    openvdb::Vec3SGrid::Ptr vel = openvdb::Vec3SGrid::create();
    vel->setName("vel");
    vel->getAccessor().setValue(Coord(0, 0, 0), openvdb::Vec3s(1, 2, 3));
    const std::string p =
        write("many.vdb", {vel, constant("smoke", 1), constant("density", 2), constant("t", 3)});
    EXPECT_EQ(loadVdbDensity(p, "", {})->at(0, 0, 0), 2.0f);
    EXPECT_EQ(loadVdbDensity(p, "smoke", {})->at(0, 0, 0), 1.0f);
    EXPECT_EQ(loadVdbDensity(p, "t", {})->at(0, 0, 0), 3.0f);
    EXPECT_THAT(loadVdbDensity(p, "t", {})->name, HasSubstr("'t'"));

    // Without a "density" grid, the first float grid in the file (after a grid of vectors),
    // not the first by name.
    const std::string q = write("no-density.vdb", {vel, constant("t", 3), constant("heat", 5)});
    EXPECT_EQ(loadVdbDensity(q, "", {})->at(0, 0, 0), 3.0f);
}

TEST_F(VdbReaderTest, MissingOrWrongGridsAreNamed) {
    openvdb::Vec3SGrid::Ptr vel = openvdb::Vec3SGrid::create();
    vel->setName("vel");
    vel->getAccessor().setValue(Coord(0, 0, 0), openvdb::Vec3s(1, 2, 3));
    FloatGrid::Ptr smoke = floatGrid("smoke");
    smoke->getAccessor().setValue(Coord(0, 0, 0), 1.0f);

    const std::string onlyVectors = loadError(write("vel.vdb", {vel}));
    EXPECT_THAT(onlyVectors, HasSubstr("vel.vdb"));
    EXPECT_THAT(onlyVectors, HasSubstr("no float grid"));
    EXPECT_THAT(onlyVectors, HasSubstr("'vel' (vec3s)"));

    const std::string p = write("two.vdb", {vel, smoke});
    const std::string missing = loadError(p, "density");
    EXPECT_THAT(missing, HasSubstr("no grid named 'density'"));
    EXPECT_THAT(missing, HasSubstr("'vel' (vec3s), 'smoke' (float)"));
    EXPECT_THAT(loadError(p, "vel"), HasSubstr("grid 'vel' holds vec3s values"));

    EXPECT_THAT(loadError(write("none.vdb", {})), HasSubstr("the file holds no grids"));
}

TEST_F(VdbReaderTest, EmptyGridIsRefused) {
    FloatGrid::Ptr empty = floatGrid("density");
    // Inactive values alone (a voxel switched off) make no active box.
    empty->getAccessor().setValueOff(Coord(1, 1, 1), 4.0f);
    EXPECT_THAT(loadError(write("empty.vdb", {empty})), HasSubstr("has no active voxels"));
}

TEST_F(VdbReaderTest, DenseSizeIsLimited) {
    // Two voxels 601 apart: a 601^3 box, over 512^3, whether the file records its box or not.
    FloatGrid::Ptr far = floatGrid("density");
    far->getAccessor().setValue(Coord(0, 0, 0), 1.0f);
    far->getAccessor().setValue(Coord(600, -600, 600), 1.0f);
    for (bool stats : {true, false}) {
        const std::string message =
            loadError(write(stats ? "far.vdb" : "far-nostats.vdb", {far}, stats));
        EXPECT_THAT(message, HasSubstr("601 x 601 x 601 = 217081801 voxels")) << stats;
        EXPECT_THAT(message, HasSubstr("134217728 (512^3)")) << stats;
    }

    // Within 512^3 but over the memory the limits allow: 20^3 floats are 32000 bytes.
    FloatGrid::Ptr box = floatGrid("density");
    box->getAccessor().setValue(Coord(0, 0, 0), 1.0f);
    box->getAccessor().setValue(Coord(19, 19, 19), 1.0f);
    const std::string p = write("box.vdb", {box});
    LoadLimits small;
    small.memoryBytes = 20000;
    EXPECT_THAT(loadError(p, "", small), HasSubstr("20 x 20 x 20 = 8000 voxels"));
    EXPECT_THAT(loadError(p, "", small), HasSubstr("available"));
    LoadLimits enough;
    enough.memoryBytes = 64 << 20;
    EXPECT_EQ(loadVdbDensity(p, "", enough)->nx, 20);
}

TEST_F(VdbReaderTest, FrustumTransformIsRefused) {
    FloatGrid::Ptr grid = floatGrid("density");
    grid->getAccessor().setValue(Coord(0, 0, 0), 1.0f);
    grid->setTransform(openvdb::math::Transform::createFrustumTransform(
        openvdb::BBoxd(openvdb::Vec3d(0), openvdb::Vec3d(10)), 0.5, 2.0, 1.0));
    const std::string message = loadError(write("frustum.vdb", {grid}));
    EXPECT_THAT(message, HasSubstr("Frustum"));
    EXPECT_THAT(message, HasSubstr("only linear"));
}

TEST_F(VdbReaderTest, BadFilesGiveMessages) {
    EXPECT_THAT(loadError(path("absent.vdb")), HasSubstr("absent.vdb': No such file"));
    EXPECT_THAT(loadError(dir_.string()), HasSubstr("directory"));
    { std::ofstream(path("text.vdb")) << "not a VDB file at all\n"; }
    EXPECT_THAT(loadError(path("text.vdb")), HasSubstr("text.vdb"));

    // An OpenVDB stream (no grid offsets) saved as a file.
    FloatGrid::Ptr grid = floatGrid("density");
    grid->getAccessor().setValue(Coord(0, 0, 0), 1.0f);
    {
        std::ofstream out(path("stream.vdb"), std::ios::binary);
        openvdb::io::Stream(out).write(openvdb::GridCPtrVec{grid});
    }
    EXPECT_THAT(loadError(path("stream.vdb")), HasSubstr("no grid offsets"));
}

TEST_F(VdbReaderTest, TruncatedFilesGiveMessages) {
    // A grid with some leaves, cut at many lengths (half, and others): each is refused, none
    // crashes or loads garbage.
    FloatGrid::Ptr grid = floatGrid("density");
    auto acc = grid->getAccessor();
    for (int i = 0; i < 40; ++i)
        acc.setValue(Coord(i, (i * 7) % 13, (i * 5) % 11), 0.5f + static_cast<float>(i));
    const std::string whole = write("whole.vdb", {grid});
    const auto size = std::filesystem::file_size(whole);
    ASSERT_FALSE(loadError(whole).size());
    std::ifstream in(whole, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    for (size_t cut : {size / 2, size / 8, size / 3, size * 3 / 4, size - 1, size_t(8)}) {
        const std::string p = path("cut-" + std::to_string(cut) + ".vdb");
        std::ofstream(p, std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(cut));
        const std::string message = loadError(p);
        EXPECT_THAT(message, HasSubstr(p)) << cut << " of " << size;
        if (cut > size / 2) {
            EXPECT_THAT(message, HasSubstr("truncated")) << cut << " of " << size;
        }
    }
}

/// The bytes of `path`, and `bytes` written to `path`.
std::string readBytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}
void writeBytes(const std::string& path, const std::string& bytes) {
    std::ofstream(path, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
}
std::string le32(uint32_t v) {
    std::string s(4, '\0');
    for (int i = 0; i < 4; ++i) s[i] = static_cast<char>((v >> (8 * i)) & 0xff);
    return s;
}

TEST_F(VdbReaderTest, CorruptCountsAndLengthsAreRefusedBeforeOpenVdbAllocatesThem) {
    // OpenVDB allocates what a string length, a metadata size or a node count says before it
    // reads: each corrupt count here is found from the file's own bytes first, with a message,
    // in a few milliseconds and without gigabytes (fuzz/vdb_fuzzer.cpp found each kind).
    FloatGrid::Ptr grid = floatGrid("density");
    grid->getAccessor().setValue(Coord(0, 0, 0), 1.0f);
    grid->getAccessor().setValue(Coord(5000, 0, 0), 2.0f);  // a second child of the root
    openvdb::io::File file(path("good.vdb"));
    file.setCompression(openvdb::io::COMPRESS_ACTIVE_MASK);  // the values as they are
    tbb::task_arena(1).execute([&] { file.write({grid}); });
    file.close();
    const std::string good = readBytes(path("good.vdb"));
    ASSERT_EQ(loadError(path("good.vdb")), "");
    auto patched = [&](const std::string& name, const std::string& find, size_t offset,
                       const std::string& with) {
        std::string bytes = good;
        const size_t at = bytes.find(find);
        EXPECT_NE(at, std::string::npos) << name;
        if (at != std::string::npos) bytes.replace(at + offset, with.size(), with);
        writeBytes(path(name), bytes);
        return loadError(path(name));
    };
    // The grid's name in the table of grids: its length 7 before "density", made 2^31.
    EXPECT_THAT(patched("name.vdb", le32(7) + "density", 0, le32(1u << 31)),
                HasSubstr("a grid's name runs past the end of"));
    // A metadata value of a fixed-size type (the active box's corner, a vec3i) stated shorter:
    // OpenVDB would read its 12 bytes anyway and lose its place.
    EXPECT_THAT(patched("vec3i.vdb", "vec3i" + le32(12), 5, le32(4)),
                HasSubstr("a grid's metadata"));
    // The root's child count (after the tree's buffer count 1, the background 0, no tiles).
    const std::string root = le32(1) + le32(0) + le32(0) + le32(2);
    EXPECT_THAT(patched("children.vdb", root, 12, le32(0x7fffffff)),
                HasSubstr("runs past the end of its part of the file"));
    // The second child's origin (4096, 0, 0) made the first's (0, 0, 0).
    EXPECT_THAT(patched("twice.vdb", le32(4096) + le32(0) + le32(0), 0, le32(0)),
                HasSubstr("two of the root's children have the same origin"));
}

TEST_F(VdbReaderTest, ASmokeGridRendersFromASceneFile) {
    // A ball of smoke (density 4 inside radius 8 voxels, voxel size 0.1: a ball of radius 0.8)
    // written with OpenVDB, placed by a scene file's transform, in front of a white emitter:
    // the pixels through it are darker than those beside it: 1.6 units of density 4 times
    // sigma_t 0.5 at its middle let exp(-3.2) = 4% through, plus what scatters towards the eye.
    FloatGrid::Ptr grid = floatGrid("density");
    grid->setTransform(openvdb::math::Transform::createLinearTransform(0.1));
    auto acc = grid->getAccessor();
    for (int x = -8; x <= 8; ++x)
        for (int y = -8; y <= 8; ++y)
            for (int z = -8; z <= 8; ++z)
                if (x * x + y * y + z * z <= 64) acc.setValue(Coord(x, y, z), 4.0f);
    const std::string file = write("smoke.vdb", {grid});
    const std::string text =
        "size 21 5\nintegrator path\ncamera 0 0 6  0 0 0  0 1 0  12\n"
        "maxdepth 2\nquadLight -5 -5 -4  10 0 0  0 10 0  1 1 1\n"
        "translate -0.5 0 0\nmedium smoke absorption 0.1 0.1 0.1 "
        "scattering 0.4 0.4 0.4 density " +
        file + "\nfog smoke\n";
    auto scene = test::preparedScene(text);
    ASSERT_EQ(scene->media.size(), 1u);
    RenderOptions o;
    o.spp = 64;
    o.threads = 2;
    const Film film = render(*scene, o).film;
    // The camera sees [-2.65, 2.65] across at the ball's distance: column 8 looks through the
    // ball's middle (moved 0.5 to the left), the last column sees the light unhindered.
    const double left = film.at(8, 2).x, right = film.at(20, 2).x;
    EXPECT_NEAR(right, 1, 1e-9);
    EXPECT_LT(left, 0.3);
    EXPECT_GT(left, 0);  // some light scatters through
}

#endif

}  // namespace
}  // namespace glint
