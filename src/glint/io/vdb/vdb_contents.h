#pragma once
/// The table of contents of an OpenVDB file: its grids in file order, read as io::File::open
/// reads it, for vdb_reader.cpp. io::File keeps that table to itself (in name order), and reads
/// a truncated file's last grid past the end without a word, filling its last voxels with
/// whatever it finds: where each grid ends is how a truncated file is told apart.

#include <openvdb/Grid.h>

#include <cstdint>
#include <string>
#include <vector>

namespace glint::vdb {

struct GridEntry {
    std::string name;
    std::string valueType;  ///< OpenVDB's name of it: "float", "double", "vec3s", ...
    bool isFloat = false;   ///< A FloatGrid (what densities are read from).
    int64_t end = 0;        ///< The offset just past the grid's bytes in the file.
};

/// The grids of the OpenVDB file at `path`, in file order. Needs openvdb::initialize() first.
/// Throws (OpenVDB's exceptions, or std::runtime_error) for a file that is not a VDB file, is
/// truncated (a grid ends beyond the file), or has no grid offsets (written by io::Stream: such
/// files are read whole, which Glint does not do).
std::vector<GridEntry> readContents(const std::string& path);

/// The grid `name` of the file at `path`, read as io::File::readGridMetadata (`metadataOnly`)
/// or io::File::readGrid reads it (all of it now, no delayed loading), after the checks of
/// readContents. Besides those, the lengths and counts OpenVDB reads before a grid's topology
/// are checked against the bytes the file has before OpenVDB allocates what they say, and the
/// grid is read from a stream that throws std::ios_base::failure at the first read past the
/// file's end: a corrupt count in the topology makes OpenVDB loop until the file ends, not 2^32
/// times. Throws as readContents, and std::runtime_error if there is no grid `name`.
openvdb::GridBase::Ptr readGrid(const std::string& path, const std::string& name,
                                bool metadataOnly);

}  // namespace glint::vdb
