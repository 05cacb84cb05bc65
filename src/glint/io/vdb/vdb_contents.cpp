// An OpenVDB file's grids in file order (vdb_contents.h): io::File::open's reading of the header
// and grid descriptors, through the protected members of io::Archive that it uses.

#include "glint/io/vdb/vdb_contents.h"

#include <openvdb/io/Archive.h>
#include <openvdb/io/GridDescriptor.h>
#include <openvdb/io/io.h>
#include <openvdb/openvdb.h>

#include <fstream>
#include <stdexcept>

namespace glint::vdb {
namespace {

class ContentsReader : public openvdb::io::Archive {
  public:
    std::vector<GridEntry> read(const std::string& path) {
        std::ifstream is(path, std::ios_base::in | std::ios_base::binary);
        if (!is) throw std::runtime_error("cannot open the file");
        is.seekg(0, std::ios_base::end);
        const int64_t size = is.tellg();
        is.seekg(0);
        readHeader(is);  // Throws for a file that is not a VDB file.
        auto meta = std::make_shared<openvdb::io::StreamMetadata>();
        meta->setSeekable(true);
        openvdb::io::setStreamMetadataPtr(is, meta, /*transfer=*/false);
        setFormatVersion(is);
        setLibraryVersion(is);
        setDataCompression(is);
        openvdb::MetaMap().readMeta(is);
        if (!is) throw std::runtime_error("the file is truncated: it ends inside its header");
        if (!inputHasGridOffsets())
            throw std::runtime_error(
                "the file has no grid offsets (an OpenVDB stream, io::Stream); Glint reads "
                "files written by io::File, as OpenVDB's tools and DCCs write them");
        std::vector<GridEntry> grids;
        const int32_t count = readGridCount(is);
        for (int32_t i = 0; i < count && is; ++i) {
            openvdb::io::GridDescriptor gd;
            const openvdb::GridBase::Ptr grid = gd.read(is);
            if (!is || !grid) break;
            if (gd.getEndPos() > size || gd.getEndPos() < gd.getGridPos())
                throw std::runtime_error("the file is truncated: grid '" + gd.gridName() +
                                         "' ends at byte " + std::to_string(gd.getEndPos()) +
                                         ", the file has " + std::to_string(size));
            grids.push_back(GridEntry{gd.gridName(), grid->valueType(),
                                      grid->isType<openvdb::FloatGrid>(), gd.getEndPos()});
            gd.seekToEnd(is);
        }
        if (!is || static_cast<int32_t>(grids.size()) != count)
            throw std::runtime_error("the file is truncated: it ends inside its table of grids");
        return grids;
    }
};

}  // namespace

std::vector<GridEntry> readContents(const std::string& path) { return ContentsReader().read(path); }

}  // namespace glint::vdb
