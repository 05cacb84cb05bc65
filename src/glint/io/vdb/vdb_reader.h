#pragma once
/// Reading density grids from OpenVDB files (.vdb) into scene/'s dense DensityGrid. Only this
/// folder sees OpenVDB's types (vdb_reader.cpp, vdb_contents.cpp), and only the OpenVDB module
/// links them (vdb_module.h: libglint_vdb.so, loaded by vdb_loader.cpp the first time a file is
/// read, so that runs that read none pay nothing for OpenVDB); builds without the library (the
/// web build, GLINT_OPENVDB=OFF) link vdb_reader_none.cpp, which refuses every file.

#include <memory>
#include <string>

#include "glint/core/input_file.h"
#include "glint/scene/medium.h"

namespace glint {

/// Most voxels a dense copy may have (512^3: 512 MiB of floats), whatever the memory.
constexpr long long kMaxDensityVoxels = 512LL * 512 * 512;

/// Reads one float grid of the OpenVDB file at `path` as a dense density grid.
///
/// Which grid: the one named `gridName`; when that is empty, the float grid named "density",
/// else the first float grid in the file's order (FloatGrid; grids of other value types are
/// never read).
///
/// What is copied: the box of the grid's active voxels (its active voxel bounding box, in
/// OpenVDB's index space), voxel for voxel: active voxels and active tiles give their values,
/// inactive ones inside the box the grid's background; outside the box the density is 0
/// (DensityGrid::lookup). Negative values (and a negative background) become 0; a value that
/// is NaN or infinite is an error naming the voxel.
///
/// Placement: OpenVDB puts voxel centres at integer index coordinates; Glint's voxel (i, j, k)
/// covers [i, i + 1] x [j, j + 1] x [k, k + 1]. So the dense voxel (i, j, k) is OpenVDB's voxel
/// (i, j, k) + the box's minimum corner, and `worldFromIndex` = the grid's own index-to-world
/// map (voxel size, rotation, translation: any linear OpenVDB map) after a translation by
/// (minimum corner - 0.5). World space is the file's: where the medium sits in the scene is the
/// caller's business (a scene transform on top).
///
/// Limits, checked before the dense copy is allocated (and, from the box and memory the file's
/// metadata records for the grid, before its voxels are read): at most kMaxDensityVoxels voxels,
/// and its bytes (4 a voxel) within memoryAvailable(limits), with the grid's own before reading.
/// `limits.readFiles` is the caller's to check.
///
/// Throws RenderError ("cannot read density grid 'PATH': why") for a missing, unreadable,
/// truncated (a grid ending beyond the file) or corrupt file, an OpenVDB stream (io::Stream's
/// files, without grid offsets), a file without the grid (the message lists the grids it has and
/// their types), a grid without active voxels, a non-linear (frustum) or singular transform,
/// too many voxels (the message gives the size), a non-finite value, a build without OpenVDB,
/// or an OpenVDB module that cannot be loaded (the message says where it was looked for). A scene
/// parser reports it at its command's file:line:col, as Parser::sceneImage does for textures.
///
/// A corrupt file's structure is OpenVDB's parser's to check, and it trusts the lengths and
/// counts it reads: such a file can make it allocate much more than the file holds before it
/// fails (std::bad_alloc is caught and reported as above). Glint's own checks bound the dense
/// copy, and find truncated files (vdb_contents.h). OpenVDB's parallel algorithms run on the
/// calling thread alone (an arena of one slot): reading starts no TBB threads.
std::shared_ptr<const DensityGrid> loadVdbDensity(const std::string& path,
                                                  const std::string& gridName,
                                                  const LoadLimits& limits = {});

}  // namespace glint
