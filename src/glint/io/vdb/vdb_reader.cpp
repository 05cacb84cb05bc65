// Density grids from OpenVDB files (vdb_reader.h), with vdb_contents.cpp the only files that see
// OpenVDB's types. The file's table of grids first (vdb_contents.h), then the chosen grid's
// metadata (its size as the file records it), then its voxels, then the dense copy.

#include "glint/io/vdb/vdb_reader.h"

#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <mutex>
#include <new>

#include "glint/core/error.h"
#include "glint/core/system.h"
#include "glint/io/vdb/vdb_contents.h"
#include "glint/io/vdb/vdb_module.h"

namespace glint {
namespace {

using openvdb::CoordBBox;
using openvdb::FloatGrid;
using openvdb::GridBase;

[[noreturn]] void cannot(const std::string& path, const std::string& why) {
    throw RenderError("cannot read density grid '" + path + "': " + why);
}

/// openvdb::initialize() registers the grid types and codecs; once, whichever thread comes first.
void initializeOpenVdb() {
    static std::once_flag once;
    std::call_once(once, [] { openvdb::initialize(); });
}

std::string quote(const std::string& s) { return "'" + s + "'"; }

/// "'density' (float), 'v' (vec3s)": the grids of a file and their value types, for messages.
std::string listGrids(const std::vector<vdb::GridEntry>& grids) {
    if (grids.empty()) return "the file holds no grids";
    std::string list = "the file's grids: ";
    for (size_t i = 0; i < grids.size(); ++i)
        list += (i ? ", " : "") + quote(grids[i].name) + " (" + grids[i].valueType + ")";
    return list;
}

/// The name of the grid to read: `gridName`, or "density", or the first float grid in the file.
std::string pickGrid(const std::string& path, const std::vector<vdb::GridEntry>& grids,
                     const std::string& gridName) {
    if (!gridName.empty()) {
        for (const vdb::GridEntry& g : grids) {
            if (g.name != gridName) continue;
            if (!g.isFloat)
                cannot(path, "grid " + quote(gridName) + " holds " + g.valueType +
                                 " values, not float densities");
            return g.name;
        }
        cannot(path, "no grid named " + quote(gridName) + "; " + listGrids(grids));
    }
    for (const vdb::GridEntry& g : grids)
        if (g.name == "density" && g.isFloat) return g.name;
    for (const vdb::GridEntry& g : grids)
        if (g.isFloat) return g.name;
    cannot(path, "no float grid to read densities from; " + listGrids(grids));
}

/// Voxels along each axis of the box from `lo` to `hi` (inclusive), in 64 bits: OpenVDB's
/// coordinates span all of int32.
struct BoxSize {
    long long nx, ny, nz;
    BoxSize(const openvdb::Coord& lo, const openvdb::Coord& hi)
        : nx(1LL + hi.x() - lo.x()), ny(1LL + hi.y() - lo.y()), nz(1LL + hi.z() - lo.z()) {}
    double voxels() const {
        return static_cast<double>(nx) * static_cast<double>(ny) * static_cast<double>(nz);
    }
    std::string str() const {
        char count[32];
        std::snprintf(count, sizeof count, "%.0f", voxels());
        return std::to_string(nx) + " x " + std::to_string(ny) + " x " + std::to_string(nz) +
               " = " + count + " voxels";
    }
};

/// Refuses a dense copy of `size` over kMaxDensityVoxels, or over the memory available with the
/// `gridBytes` the grid itself takes.
void checkSize(const std::string& path, const std::string& name, const BoxSize& size,
               double gridBytes, const LoadLimits& limits) {
    if (size.voxels() > static_cast<double>(kMaxDensityVoxels))
        cannot(path, "grid " + quote(name) + "'s active voxels span " + size.str() +
                         ", more than the " + std::to_string(kMaxDensityVoxels) +
                         " (512^3) a dense density grid may have");
    const double needed = size.voxels() * sizeof(float) + gridBytes;
    if (size_t available = memoryAvailable(limits);
        available > 0 && needed > static_cast<double>(available))
        cannot(path, "grid " + quote(name) + " (" + size.str() + ") needs about " +
                         formatBytes(needed) + ", more than the " +
                         formatBytes(static_cast<double>(available)) + " available");
}

/// The same check from the box and memory the file records for the grid (OpenVDB writes them
/// unless told not to), before its voxels are read.
void checkRecordedSize(const std::string& path, const GridBase& meta, const LoadLimits& limits) {
    auto lo = meta.getMetadata<openvdb::Vec3IMetadata>(GridBase::META_FILE_BBOX_MIN);
    auto hi = meta.getMetadata<openvdb::Vec3IMetadata>(GridBase::META_FILE_BBOX_MAX);
    if (!lo || !hi) return;
    const openvdb::Coord a(lo->value()), b(hi->value());
    if (a.x() > b.x() || a.y() > b.y() || a.z() > b.z()) return;  // Empty: said after reading.
    auto bytes = meta.getMetadata<openvdb::Int64Metadata>(GridBase::META_FILE_MEM_BYTES);
    checkSize(path, meta.getName(), BoxSize(a, b),
              bytes ? static_cast<double>(std::max<int64_t>(bytes->value(), 0)) : 0, limits);
}

/// worldFromIndex: Glint's index space to OpenVDB's (voxel centres from i + 0.5 to the integer
/// coordinate i + lo), then the grid's own index-to-world map.
Transform placement(const std::string& path, const FloatGrid& grid, const openvdb::Coord& lo) {
    const openvdb::math::Transform& xf = grid.transform();
    if (!xf.isLinear())
        cannot(path, "grid " + quote(grid.getName()) + " has a " + xf.mapType() +
                         " transform; Glint places only linear (affine) ones");
    // OpenVDB multiplies row vectors: world = (x, y, z, 1) * m, the translation in the last row.
    const openvdb::Mat4d m = xf.baseMap()->getAffineMap()->getMat4();
    Mat4 worldFromVdb;
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) worldFromVdb.m[r][c] = m(c, r);
    const Mat4 vdbFromIndex = Mat4::translate(lo.x() - 0.5, lo.y() - 0.5, lo.z() - 0.5);
    std::optional<Transform> t = Transform::fromMatrix(worldFromVdb * vdbFromIndex);
    if (!t)
        cannot(path, "grid " + quote(grid.getName()) +
                         "'s transform is singular or not finite: it places no volume");
    return *t;
}

/// A density from a grid value: negatives become 0, NaN and infinities are refused.
float densityOf(const std::string& path, const FloatGrid& grid, float v, const std::string& where) {
    if (!std::isfinite(v))
        cannot(path, "grid " + quote(grid.getName()) + " has the value " + std::to_string(v) +
                         " at " + where + "; densities must be finite");
    return std::max(v, 0.0f);
}

std::string coordStr(const openvdb::Coord& c) {
    return "voxel (" + std::to_string(c.x()) + ", " + std::to_string(c.y()) + ", " +
           std::to_string(c.z()) + ")";
}

/// The dense copy of the box: background everywhere, then every active voxel and tile.
void fillDense(const std::string& path, const FloatGrid& grid, const CoordBBox& box,
               DensityGrid& dense) {
    const openvdb::Coord lo = box.min();
    dense.density.assign(static_cast<size_t>(dense.nx) * dense.ny * dense.nz,
                         densityOf(path, grid, grid.background(), "its background"));
    auto set = [&](const openvdb::Coord& c, float d) {
        const size_t i = c.x() - lo.x(), j = c.y() - lo.y(), k = c.z() - lo.z();
        dense.density[(k * dense.ny + j) * dense.nx + i] = d;
    };
    for (FloatGrid::ValueOnCIter it = grid.cbeginValueOn(); it; ++it) {
        if (it.isVoxelValue()) {
            set(it.getCoord(), densityOf(path, grid, *it, coordStr(it.getCoord())));
            continue;
        }
        CoordBBox tile;
        it.getBoundingBox(tile);
        const float d = densityOf(path, grid, *it, "the tile at " + coordStr(tile.min()));
        tile.intersect(box);
        // 64-bit counters: a box may end at the largest int32 coordinate.
        for (long long z = tile.min().z(); z <= tile.max().z(); ++z)
            for (long long y = tile.min().y(); y <= tile.max().y(); ++y)
                for (long long x = tile.min().x(); x <= tile.max().x(); ++x)
                    set(openvdb::Coord(static_cast<int>(x), static_cast<int>(y),
                                       static_cast<int>(z)),
                        d);
    }
}

std::shared_ptr<const DensityGrid> readDensity(const std::string& path, const std::string& gridName,
                                               const LoadLimits& limits) {
    // The table of contents first: which grids, and whether the file holds all their bytes.
    const std::string name = pickGrid(path, vdb::readContents(path), gridName);
    checkRecordedSize(path, *vdb::readGrid(path, name, /*metadataOnly=*/true), limits);
    const FloatGrid::Ptr grid =
        openvdb::gridPtrCast<FloatGrid>(vdb::readGrid(path, name, /*metadataOnly=*/false));
    if (!grid) cannot(path, "grid " + quote(name) + " did not read as a float grid");

    const CoordBBox box = grid->evalActiveVoxelBoundingBox();
    if (box.empty()) cannot(path, "grid " + quote(name) + " has no active voxels");
    const BoxSize size(box.min(), box.max());
    checkSize(path, name, size, 0, limits);  // The grid's own memory is taken by now.

    auto dense = std::make_shared<DensityGrid>();
    dense->nx = static_cast<int>(size.nx);
    dense->ny = static_cast<int>(size.ny);
    dense->nz = static_cast<int>(size.nz);
    dense->worldFromIndex = placement(path, *grid, box.min());
    dense->name = path + " (grid " + quote(name) + ")";
    fillDense(path, *grid, box, *dense);
    return dense;
}

}  // namespace

std::shared_ptr<const DensityGrid> readVdbDensity(const std::string& path,
                                                  const std::string& gridName,
                                                  const LoadLimits& limits) {
    // Any size: OpenVDB seeks to the one grid it reads, whose size is checked on its own.
    if (std::string problem = inputFileProblem(path, std::numeric_limits<long long>::max());
        !problem.empty())
        cannot(path, problem);
    initializeOpenVdb();
    try {
        // OpenVDB's parallel algorithms (the active box) run in TBB's thread pool: here in an
        // arena of one slot, this thread's, so that reading starts no threads of TBB's beside
        // Glint's own (core/parallel.h).
        tbb::task_arena arena(1);
        std::shared_ptr<const DensityGrid> grid;
        arena.execute([&] { grid = readDensity(path, gridName, limits); });
        return grid;
    } catch (const RenderError&) {
        throw;
    } catch (const std::bad_alloc&) {
        cannot(path, "out of memory while reading it (is the file corrupt?)");
    } catch (const std::exception& e) {
        // OpenVDB's exceptions say what failed ("IoError: ..."), not which file.
        cannot(path, e.what());
    }
}

}  // namespace glint
