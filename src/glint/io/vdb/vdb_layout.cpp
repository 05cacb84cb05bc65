// The walk of a float grid's layout (vdb_layout.h). The layout, as OpenVDB 10's headers read it:
//   topology: int32 buffer count; the root's float background, uint32 tile and child counts,
//     each tile 3 int32 + float + bool, each child 3 int32 and an internal node;
//   an internal node (32^3, then 16^3 entries): its child mask and value mask (a bit per
//     entry), its values compressed (below), then its children in the order of the child mask;
//     a leaf (8^3 voxels): its value mask;
//   buffers, from blockPos: every leaf in the tree's order (the root's children sorted by origin,
//     then each node's children by position): its value mask again and its values compressed;
//   values compressed (io::readCompressedValues): a byte saying what follows: 0, 1 or 2 inactive
//     values, and a selection mask of the node's size; then the values, all of the node's or
//     only its active ones (COMPRESS_ACTIVE_MASK), each 4 bytes or 2 (half floats), raw or, with
//     COMPRESS_ZIP or COMPRESS_BLOSC, as an int64 size and that many bytes (a size <= 0 stands
//     for -size raw bytes).

#include "glint/io/vdb/vdb_layout.h"

#include <algorithm>
#include <array>
#include <bit>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace glint::vdb {
namespace {

class LayoutWalk : BoundedReader {
  public:
    LayoutWalk(std::istream& is, ValueLayout layout)
        : BoundedReader(is, 0), layout_(layout), valueBytes_(layout.half ? 2 : 4) {}

    void topology(int64_t end) {
        end_ = end;
        number<int32_t>("the tree's buffer count");
        number<float>("the root's background");
        const auto tiles = number<uint32_t>("the root's tile count");
        const auto children = number<uint32_t>("the root's child count");
        skip(uint64_t(tiles) * (3 * 4 + 4 + 1), "the root's tiles");
        for (uint32_t n = 0; n < children; ++n) {
            Root child;
            for (int32_t& c : child.origin) c = number<int32_t>("a root child's origin");
            leaves_ = &child.leafActive;
            internal(5);
            roots_.push_back(std::move(child));
        }
        // OpenVDB keys the root's children by origin: a repeated one would replace (and leak)
        // the child read before.
        std::sort(roots_.begin(), roots_.end(),
                  [](const Root& a, const Root& b) { return a.origin < b.origin; });
        for (size_t i = 1; i < roots_.size(); ++i)
            if (roots_[i].origin == roots_[i - 1].origin)
                fail("two of the root's children have the same origin");
    }

    void buffers(int64_t end) {
        end_ = end;
        for (const Root& root : roots_)
            for (int active : root.leafActive) {
                skip(kLeafValues / 8, "a leaf's value mask");
                values(kLeafValues, active, "a leaf's values");
            }
    }

  private:
    static constexpr uint32_t kLeafValues = 512;
    struct Root {
        std::array<int32_t, 3> origin{};
        std::vector<int> leafActive;  ///< Each leaf's active voxels, in the tree's order.
    };

    /// An internal node of 2^(3 log2Dim) entries, whose children are internal nodes of
    /// log2Dim - 1 or, below 4, leaves.
    void internal(int log2Dim) {
        const uint32_t entries = 1u << (3 * log2Dim);
        std::vector<uint64_t> childMask(entries / 64), valueMask(entries / 64);
        read(childMask.data(), entries / 8, "a node's child mask");
        read(valueMask.data(), entries / 8, "a node's value mask");
        values(entries, popcount(valueMask), "a node's values");
        for (uint32_t word = 0; word < childMask.size(); ++word)
            for (uint64_t bits = childMask[word]; bits; bits &= bits - 1) {
                if (log2Dim > 4) {
                    internal(log2Dim - 1);
                } else {
                    std::array<uint64_t, kLeafValues / 64> mask{};
                    read(mask.data(), kLeafValues / 8, "a leaf's value mask");
                    leaves_->push_back(static_cast<int>(popcount(mask)));
                }
            }
    }

    /// io::readCompressedValues of `count` values of which `active` are on.
    void values(uint32_t count, uint32_t active, const char* what) {
        const auto meta = number<int8_t>(what);
        if (meta < 0 || meta > 6) fail(std::string(what) + " has an unknown compression mode");
        if (meta == 2 || meta == 4 || meta == 5) skip(valueBytes_, what);  // inactive value 0
        if (meta == 5) skip(valueBytes_, what);                            // inactive value 1
        if (meta == 3 || meta == 4 || meta == 5) skip(count / 8, what);    // selection mask
        const bool maskCompressed = layout_.compression & openvdb::io::COMPRESS_ACTIVE_MASK;
        const uint32_t stored = maskCompressed && meta != 6 ? active : count;
        const uint64_t bytes = uint64_t(stored) * valueBytes_;
        if (layout_.compression & (openvdb::io::COMPRESS_ZIP | openvdb::io::COMPRESS_BLOSC)) {
            const auto size = number<int64_t>(what);
            if (size <= 0) {
                if (static_cast<uint64_t>(-(size + 1)) + 1 != bytes)
                    fail(std::string(what) + " have the wrong size");
                skip(bytes, what);
            } else {
                skip(static_cast<uint64_t>(size), what);
            }
        } else {
            skip(bytes, what);
        }
    }

    template <size_t N>
    static uint32_t popcount(const std::array<uint64_t, N>& words) {
        uint32_t n = 0;
        for (uint64_t w : words) n += std::popcount(w);
        return n;
    }
    static uint32_t popcount(const std::vector<uint64_t>& words) {
        uint32_t n = 0;
        for (uint64_t w : words) n += std::popcount(w);
        return n;
    }

    ValueLayout layout_;
    int valueBytes_;
    std::vector<Root> roots_;
    std::vector<int>* leaves_ = nullptr;
};

}  // namespace

void BoundedReader::read(void* into, uint64_t bytes, const std::string& what) {
    room(bytes, what);
    is_.read(static_cast<char*>(into), static_cast<std::streamsize>(bytes));
    if (!is_) fail(what + " runs past the end of the file");
}

void BoundedReader::skip(uint64_t bytes, const std::string& what) {
    room(bytes, what);
    is_.seekg(static_cast<std::streamoff>(bytes), std::ios_base::cur);
}

void BoundedReader::room(uint64_t bytes, const std::string& what) const {
    const int64_t at = is_.tellg();
    if (at < 0 || at > end_ || bytes > static_cast<uint64_t>(end_ - at))
        fail(what + " runs past the end of its part of the file");
}

void BoundedReader::fail(const std::string& why) {
    throw std::runtime_error("the file is truncated or corrupt: " + why);
}

void checkFloatTreeLayout(std::istream& is, ValueLayout layout, int64_t blockPos, int64_t endPos) {
    LayoutWalk walk(is, layout);
    walk.topology(blockPos);
    is.seekg(blockPos);
    walk.buffers(endPos);
}

}  // namespace glint::vdb
