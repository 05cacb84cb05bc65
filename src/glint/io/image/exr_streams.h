#pragma once
/// OpenEXR streams over memory, shared by the image (exr.cpp) and frame-piece (exr_piece.cpp)
/// readers and writers. Internal to io/image.

#include <Iex.h>
#include <ImfIO.h>
#include <ImfInputFile.h>
#include <ImfThreading.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <mutex>
#include <string>
#include <string_view>

#include "glint/core/parallel.h"

namespace glint::exr_detail {

/// Lets OpenEXR compress a file's chunks on every hardware thread (its global pool, started by
/// the first call; by default it uses the calling thread alone). Writers only: the bytes written
/// are the same for any count, and a 3840x2160 frame's ZIP write took 2.7 s on one thread.
/// Readers keep one thread: with N, OpenEXR allocates 2N line buffers of the size a file's header
/// claims before anything is checked, and a hostile piece then cost the fuzzer 2 GB and 15 s.
inline void useAllThreads() {
    static std::once_flag once;
    std::call_once(once, [] { Imf::setGlobalThreadCount(hardwareThreads()); });
}

/// Checks the sizes the attributes of an OpenEXR file's headers claim against the file's bytes
/// before OpenEXR reads them: OpenEXR allocates what a string, opaque or vector attribute claims
/// before it finds the file too short (fuzzed pieces of a few kB claimed 1.8 GB: 15 s and 2 GB
/// under the fuzzer). It walks the headers as OpenEXR 3.1's Header::readFrom does, which reads
/// each value by its type's own layout rather than skipping to the claimed size (exr.cpp).
/// Throws Iex::InputExc, as OpenEXR does for a malformed file; leaves whatever else is wrong to
/// OpenEXR.
void checkAttributeSizes(std::string_view bytes);

/// An OpenEXR output stream that appends to a string. The writer seeks back to fill in the
/// table of chunk offsets, so writes may land anywhere up to the end.
class StringOStream final : public Imf::OStream {
  public:
    explicit StringOStream(std::string& out) : Imf::OStream("memory"), out_(out) {}

    void write(const char c[], int n) override {
        size_t end = pos_ + static_cast<size_t>(n);
        if (end > out_.size()) out_.resize(end);
        std::memcpy(out_.data() + pos_, c, static_cast<size_t>(n));
        pos_ = end;
    }
    uint64_t tellp() override { return pos_; }
    void seekp(uint64_t pos) override { pos_ = static_cast<size_t>(pos); }

  private:
    std::string& out_;
    size_t pos_ = 0;
};

/// An OpenEXR input stream over bytes in memory; reading past the end throws, as the library
/// expects of a stream.
class MemoryIStream final : public Imf::IStream {
  public:
    MemoryIStream(std::string_view bytes, const std::string& name)
        : Imf::IStream(name.c_str()), bytes_(bytes) {}

    bool read(char c[], int n) override {
        if (n < 0 || static_cast<size_t>(n) > bytes_.size() - std::min(pos_, bytes_.size()))
            throw Iex::InputExc("unexpected end of file");
        std::memcpy(c, bytes_.data() + pos_, static_cast<size_t>(n));
        pos_ += static_cast<size_t>(n);
        return pos_ < bytes_.size();
    }
    uint64_t tellg() override { return pos_; }
    void seekg(uint64_t pos) override { pos_ = static_cast<size_t>(pos); }

  private:
    std::string_view bytes_;
    size_t pos_ = 0;
};

/// An OpenEXR file opened from bytes in memory, as every reader opens one: the header's
/// attribute sizes checked first (checkAttributeSizes), then read on the calling thread alone
/// (see useAllThreads).
class MemoryInputFile {
  public:
    MemoryInputFile(std::string_view bytes, const std::string& name)
        : stream_((checkAttributeSizes(bytes), bytes), name), file_(stream_, 0) {}
    Imf::InputFile& file() { return file_; }

  private:
    MemoryIStream stream_;
    Imf::InputFile file_;
};

}  // namespace glint::exr_detail
