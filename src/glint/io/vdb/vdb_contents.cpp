// An OpenVDB file's grids in file order, and one grid read (vdb_contents.h): io::File's reading of
// the header, the grid descriptors and a grid, through the protected members of io::Archive that
// it uses.

#include "glint/io/vdb/vdb_contents.h"

#include <openvdb/io/Archive.h>
#include <openvdb/io/GridDescriptor.h>
#include <openvdb/io/io.h>
#include <openvdb/openvdb.h>

#include <cstdint>
#include <fstream>
#include <istream>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

#include "glint/io/vdb/vdb_layout.h"

namespace glint::vdb {
namespace {

/// OpenVDB reads a string as a 32-bit length and then allocates that many bytes before it reads
/// them, and a metadata value likewise: a corrupt length in a small file makes it allocate up to
/// 4 GiB. These walk the same bytes first, from where the stream is (and put it back), and throw
/// if a length or count points past `end`, so that OpenVDB only reads what the file can hold.
class LengthCheck : BoundedReader {
  public:
    LengthCheck(std::istream& is, int64_t end) : BoundedReader(is, end), start_(is.tellg()) {}
    ~LengthCheck() {
        is_.clear();
        is_.seekg(start_);
    }
    LengthCheck(const LengthCheck&) = delete;
    LengthCheck& operator=(const LengthCheck&) = delete;

    using BoundedReader::number;
    using BoundedReader::room;
    using BoundedReader::skip;
    void string(const char* what) { skip(number<uint32_t>(what), what); }
    /// A MetaMap: a count, then per entry a name, a type name and a value of a stated size.
    /// OpenVDB's delayed-loading metadata (type "__delayedload", in every grid written by
    /// OpenVDB 6 and later) has counts of its own inside, and is allocated by them.
    void metaMap(const char* what) {
        const int32_t count = number<int32_t>(what);
        if (count < 0) bad(what);
        for (int32_t i = 0; i < count; ++i) {
            string(what);
            const uint32_t typeLength = number<uint32_t>(what);
            room(typeLength, what);
            std::string type;
            if (typeLength < 64) {
                type.resize(typeLength);
                is_.read(type.data(), typeLength);
            } else {
                skip(typeLength, what);
            }
            const uint32_t size = number<uint32_t>(what);
            // OpenVDB reads a value of a fixed-size type by its type, whatever size is stated.
            if (const int fixed = fixedSize(type); fixed >= 0 && size != uint32_t(fixed)) bad(what);
            const int64_t valueEnd = static_cast<int64_t>(is_.tellg()) + size;
            skip(size, what);
            if (type == "__delayedload" && size > 0) {
                is_.seekg(valueEnd - size);
                delayedLoad(size, what);
                is_.seekg(valueEnd);
            }
        }
    }

  private:
    [[noreturn]] static void bad(const char* what) {
        fail(std::string(what) + " holds a size or count that does not fit the file");
    }

    /// The bytes of a metadata value of OpenVDB's type `type` whose size is its type's (-1 for
    /// the others: strings, delayed-loading metadata, types OpenVDB does not know).
    static int fixedSize(const std::string& type) {
        static const std::pair<const char*, int> kSizes[] = {
            {"bool", 1},    {"int32", 4},  {"int64", 8},  {"float", 4},  {"double", 8},
            {"vec2i", 8},   {"vec2s", 8},  {"vec2d", 16}, {"vec3i", 12}, {"vec3s", 12},
            {"vec3d", 24},  {"vec4i", 16}, {"vec4s", 16}, {"vec4d", 32}, {"mat4s", 64},
            {"mat4d", 128}, {"quats", 16}, {"quatd", 32}};
        for (const auto& [name, bytes] : kSizes)
            if (type == name) return bytes;
        return -1;
    }

    /// What a Blosc block may expand to beyond its list: OpenVDB pads the lists it compresses.
    static constexpr uint64_t kBloscSlack = 4096;

    /// io::DelayedLoadMetadata's value of `size` bytes: a count (one a leaf, and each leaf takes
    /// more than 64 bytes of the file), then a mask byte and an 8-byte size for each, each list
    /// either raw (a 0, then the bytes) or Blosc-compressed (its size, then a Blosc block whose
    /// header states the size it expands to, padded: OpenVDB reserves that much); the sizes'
    /// list may be absent (a size of 2^32 - 1).
    void delayedLoad(uint32_t size, const char* what) {
        const int64_t end = static_cast<int64_t>(is_.tellg()) + size;
        const auto count = number<uint32_t>(what);
        if (count > end_ / 64 + 1) bad(what);
        list(count, 1, end, what);
        list(count, 8, end, what);
    }
    void list(uint32_t count, uint32_t itemBytes, int64_t end, const char* what) {
        const auto bytes = number<uint32_t>(what);
        const uint64_t expanded = uint64_t(count) * itemBytes;
        const int64_t at = is_.tellg();
        if (itemBytes == 8 && bytes == std::numeric_limits<uint32_t>::max()) return;  // absent
        const uint64_t stored = bytes > 0 ? bytes : expanded;
        if (at < 0 || stored > static_cast<uint64_t>(end - at)) bad(what);
        if (bytes > 0) {
            // A Blosc header: 4 bytes, the expanded size (uint32), the block size, the
            // compressed size.
            if (bytes < 16) bad(what);
            is_.seekg(4, std::ios_base::cur);
            if (number<uint32_t>(what) > expanded + kBloscSlack) bad(what);
        }
        is_.seekg(at + static_cast<int64_t>(stored));
    }

    std::streampos start_;
};

class ContentsReader : public openvdb::io::Archive {
  public:
    /// Opens `path` and reads its header and table of grids.
    explicit ContentsReader(const std::string& path)
        : is_(path, std::ios_base::in | std::ios_base::binary) {
        if (!is_) throw std::runtime_error("cannot open the file");
        is_.seekg(0, std::ios_base::end);
        size_ = is_.tellg();
        is_.seekg(0);
        readTable();
    }

    const std::vector<GridEntry>& grids() const { return grids_; }

    /// The grid `name`: its metadata only, or all of it; the stream throws at the file's end.
    openvdb::GridBase::Ptr read(const std::string& name, bool metadataOnly) {
        for (size_t i = 0; i < grids_.size(); ++i) {
            if (grids_[i].name != name) continue;
            const openvdb::io::GridDescriptor& gd = descriptors_[i];
            if (!metadataOnly) checkLayout(gd);
            openvdb::GridBase::Ptr grid = openvdb::GridBase::createGrid(gd.gridType());
            // From here every read that runs short throws (std::ios_base::failure): OpenVDB's
            // loops over the counts a corrupt topology states then end with the file.
            is_.clear();
            is_.exceptions(std::ios_base::failbit | std::ios_base::badbit);
            gd.seekToGrid(is_);
            if (metadataOnly) {  // as io::File::readGridMetadata
                readGridCompression(is_);
                grid->readMeta(is_);
                grid->setName(gd.gridName());
            } else {
                readGrid(grid, gd, is_);
            }
            is_.exceptions(std::ios_base::goodbit);
            return grid;
        }
        throw std::runtime_error("the file has no grid '" + name + "'");
    }

  private:
    /// Walks a float grid's bytes before OpenVDB reads them (vdb_layout.h).
    void checkLayout(const openvdb::io::GridDescriptor& gd) {
        const uint32_t version = openvdb::io::getFormatVersion(is_);
        if (version < openvdb::OPENVDB_FILE_VERSION_NODE_MASK_COMPRESSION)
            throw std::runtime_error("the file is in OpenVDB's format " + std::to_string(version) +
                                     ", older than OpenVDB 3's (222), which Glint reads; save it "
                                     "again with a newer OpenVDB");
        if (gd.isInstance())
            throw std::runtime_error("grid '" + gd.gridName() + "' is an instance of grid '" +
                                     gd.instanceParentName() + "'; Glint reads grids stored whole");
        if (!openvdb::GridBase::createGrid(gd.gridType())->isType<openvdb::FloatGrid>())
            throw std::runtime_error("grid '" + gd.gridName() + "' is not a float grid");
        is_.clear();
        gd.seekToGrid(is_);
        ValueLayout layout;
        is_.read(reinterpret_cast<char*>(&layout.compression), sizeof layout.compression);
        layout.half = gd.saveFloatAsHalf();
        openvdb::MetaMap().readMeta(is_);  // its lengths were checked with the table
        openvdb::math::Transform().read(is_);
        if (!is_)
            throw std::runtime_error("the file is corrupt: grid '" + gd.gridName() +
                                     "' ends inside its metadata or transform");
        checkFloatTreeLayout(is_, layout, gd.getBlockPos(), gd.getEndPos());
        is_.clear();
    }

    void readTable() {
        std::istream& is = is_;
        const int64_t size = size_;
        readHeader(is);  // Throws for a file that is not a VDB file.
        meta_ = std::make_shared<openvdb::io::StreamMetadata>();  // the stream points to it
        meta_->setSeekable(true);
        openvdb::io::setStreamMetadataPtr(is, meta_, /*transfer=*/false);
        setFormatVersion(is);
        setLibraryVersion(is);
        setDataCompression(is);
        LengthCheck(is, size).metaMap("the file's metadata");
        openvdb::MetaMap().readMeta(is);
        if (!is) throw std::runtime_error("the file is truncated: it ends inside its header");
        if (!inputHasGridOffsets())
            throw std::runtime_error(
                "the file has no grid offsets (an OpenVDB stream, io::Stream); Glint reads "
                "files written by io::File, as OpenVDB's tools and DCCs write them");
        const int32_t count = readGridCount(is);
        const uint32_t version = openvdb::io::getFormatVersion(is);
        for (int32_t i = 0; i < count && is; ++i) {
            {
                LengthCheck check(is, size);
                check.string("a grid's name");
                check.string("a grid's type");
                if (version >= openvdb::OPENVDB_FILE_VERSION_GRID_INSTANCING)
                    check.string("a grid's instance parent");
            }
            openvdb::io::GridDescriptor gd;
            const openvdb::GridBase::Ptr grid = gd.read(is);
            if (!is || !grid) break;
            if (gd.getEndPos() > size || gd.getEndPos() < gd.getGridPos() || gd.getGridPos() < 0 ||
                gd.getBlockPos() < gd.getGridPos() || gd.getBlockPos() > gd.getEndPos())
                throw std::runtime_error("the file is truncated: grid '" + gd.gridName() +
                                         "' ends at byte " + std::to_string(gd.getEndPos()) +
                                         ", the file has " + std::to_string(size));
            // What io::File reads of the grid before its topology: its compression flags, its
            // metadata and its transform's type name.
            {
                const std::streampos next = is.tellg();
                is.seekg(gd.getGridPos());
                {
                    LengthCheck check(is, gd.getBlockPos());
                    if (version >= openvdb::OPENVDB_FILE_VERSION_NODE_MASK_COMPRESSION)
                        check.number<uint32_t>("a grid's compression");
                    check.metaMap("a grid's metadata");
                    if (version >= openvdb::OPENVDB_FILE_VERSION_NEW_TRANSFORM)
                        check.string("a grid's transform");
                }
                is.seekg(next);
            }
            grids_.push_back(GridEntry{gd.gridName(), grid->valueType(),
                                       grid->isType<openvdb::FloatGrid>(), gd.getEndPos()});
            descriptors_.push_back(gd);
            gd.seekToEnd(is);
        }
        if (!is || static_cast<int32_t>(grids_.size()) != count)
            throw std::runtime_error("the file is truncated: it ends inside its table of grids");
    }

    openvdb::io::StreamMetadata::Ptr meta_;
    std::ifstream is_;
    int64_t size_ = 0;
    std::vector<GridEntry> grids_;
    std::vector<openvdb::io::GridDescriptor> descriptors_;
};

}  // namespace

std::vector<GridEntry> readContents(const std::string& path) {
    return ContentsReader(path).grids();
}

openvdb::GridBase::Ptr readGrid(const std::string& path, const std::string& name,
                                bool metadataOnly) {
    return ContentsReader(path).read(name, metadataOnly);
}

}  // namespace glint::vdb
