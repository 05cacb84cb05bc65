#pragma once
/// Whether a float grid's bytes in an OpenVDB file hold what OpenVDB will read from them, walked
/// before OpenVDB reads them (vdb_contents.cpp). OpenVDB trusts every count and length it reads:
/// a corrupt one makes it allocate what the count says (a 2^63-byte zip block), loop 2^32 times,
/// or leak the nodes it drops. This walk reads the same layout with no allocation beyond a node's
/// masks and one number per leaf, and throws std::runtime_error naming the first count, length
/// or node that does not fit the file.

#include <openvdb/openvdb.h>

#include <cstdint>
#include <istream>
#include <string>

namespace glint::vdb {

/// Reads numbers from `is` and skips bytes, never past `end` (an offset in the file): the one
/// primitive of the walks here and in vdb_contents.cpp. A read or skip that would pass `end`
/// throws std::runtime_error("the file is truncated or corrupt: WHAT runs past ...").
class BoundedReader {
  public:
    BoundedReader(std::istream& is, int64_t end) : is_(is), end_(end) {}

    template <typename T>
    T number(const std::string& what) {
        T v{};
        read(&v, sizeof v, what);
        return v;
    }
    void read(void* into, uint64_t bytes, const std::string& what);
    void skip(uint64_t bytes, const std::string& what);
    /// Throws unless `bytes` more lie between where the stream is and the end.
    void room(uint64_t bytes, const std::string& what) const;
    [[noreturn]] static void fail(const std::string& why);

  protected:
    std::istream& is_;
    int64_t end_;
};

/// How the grid's values are stored: the grid's compression flags (io::COMPRESS_*) and whether
/// floats were saved as half floats.
struct ValueLayout {
    uint32_t compression = 0;
    bool half = false;
};

/// Walks a FloatGrid's topology from where `is` is (just after its transform) to `blockPos`,
/// then its leaf buffers from `blockPos` to `endPos`, as OpenVDB 10 writes them in file format
/// 222 and later (node masks compressed). Leaves `is` anywhere: the caller seeks.
void checkFloatTreeLayout(std::istream& is, ValueLayout layout, int64_t blockPos, int64_t endPos);

}  // namespace glint::vdb
