#pragma once
// Where ply_loader.cpp reads a PLY file's values from: BinarySource (either byte order) and
// AsciiSource (whitespace-separated words). Both read one value at a time, check every read
// against the bytes left, and report errors at the record being read: binary data by its byte
// offset, ASCII data by its line and column. Internal to glint/io.

#include <algorithm>
#include <array>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <string>
#include <string_view>

#include "glint/io/ply/ply_internal.h"

namespace glint::ply {

/// The record being read, for messages: "face 12", "the file ends in face 12 of 100".
class Place {
  public:
    void enter(const Element& e) { element_ = &e; }
    void at(uint64_t record) { record_ = record; }
    std::string record() const {
        return (element_ ? element_->name : std::string("data")) + " " + std::to_string(record_);
    }
    std::string recordOfCount() const {
        return record() + " of " + std::to_string(element_ ? element_->count : 0);
    }

  private:
    const Element* element_ = nullptr;
    uint64_t record_ = 0;
};

/// Binary data, from `offset` to the end of `bytes`.
class BinarySource : public Place {
  public:
    BinarySource(std::string_view bytes, size_t offset, bool bigEndian, const std::string& file)
        : begin_(reinterpret_cast<const unsigned char*>(bytes.data())),
          p_(begin_ + offset),
          end_(begin_ + bytes.size()),
          swap_(bigEndian != (std::endian::native == std::endian::big)),
          file_(file) {}

    size_t remaining() const { return static_cast<size_t>(end_ - p_); }

    /// A value of type `t` (any type) as a double: exact for every integer type.
    double real(Type t) {
        const size_t n = typeSize(t);
        if (remaining() < n) truncated();
        double v = decode(t);
        last_ = p_;
        p_ += n;
        return v;
    }
    /// A value of an integer type.
    int64_t integer(Type t) {
        double v = real(t);
        return std::isfinite(v) && std::abs(v) < 9e15 ? static_cast<int64_t>(v) : -1;
    }
    /// A list's count: not negative, and no more items of `item` than the bytes left hold.
    uint64_t count(Type t, Type item) {
        int64_t n = integer(t);
        if (n < 0) fail("a list count is negative (" + std::to_string(n) + ")");
        if (static_cast<uint64_t>(n) > remaining() / typeSize(item)) truncated();
        return static_cast<uint64_t>(n);
    }
    void skip(Type t) { skipBytes(typeSize(t)); }
    void skipItems(uint64_t n, Type t) { skipBytes(n * typeSize(t)); }  // n checked by count()
    void skipBytes(uint64_t n) {
        if (n > remaining()) truncated();
        p_ += n;
    }

    [[noreturn]] void truncated() const {
        throw SceneError({file_, 0, 0}, "the file ends in " + recordOfCount() + " (byte " +
                                            offset() + "): is it complete?");
    }
    [[noreturn]] void fail(const std::string& what) const {
        throw SceneError({file_, 0, 0},
                         record() + " (byte " + std::to_string(last_ - begin_) + "): " + what);
    }

  private:
    std::string offset() const { return std::to_string(p_ - begin_); }

    template <typename T>
    T load() const {
        std::array<unsigned char, sizeof(T)> b;
        std::memcpy(b.data(), p_, sizeof(T));
        if (swap_) std::reverse(b.begin(), b.end());
        T v;
        std::memcpy(&v, b.data(), sizeof(T));
        return v;
    }
    double decode(Type t) const {
        switch (t) {
            case Type::Int8:
                return load<int8_t>();
            case Type::UInt8:
                return load<uint8_t>();
            case Type::Int16:
                return load<int16_t>();
            case Type::UInt16:
                return load<uint16_t>();
            case Type::Int32:
                return load<int32_t>();
            case Type::UInt32:
                return load<uint32_t>();
            case Type::Float32:
                return load<float>();
            case Type::Float64:
                return load<double>();
        }
        return 0;
    }

    const unsigned char* begin_;
    const unsigned char* p_;
    const unsigned char* end_;
    const unsigned char* last_ = p_;  ///< The last value read: where errors about it point.
    bool swap_;
    const std::string& file_;
};

/// ASCII data: values are words separated by blanks and line breaks, from `offset` of `bytes`,
/// which is on line `line`.
class AsciiSource : public Place {
  public:
    AsciiSource(std::string_view bytes, size_t offset, int line, const std::string& file)
        : p_(bytes.data() + offset),
          end_(bytes.data() + bytes.size()),
          lineStart_(p_),
          line_(line),
          file_(file) {}

    /// Bytes left: a bound on the values left (each takes at least two bytes but the last).
    size_t remaining() const { return static_cast<size_t>(end_ - p_); }

    double real(Type t) {
        std::string_view w = word();
        const char* first = w.data() + (w.size() > 1 && w[0] == '+');
        const char* last = w.data() + w.size();
        if (isInteger(t)) {
            int64_t i = 0;
            if (auto [end, ec] = std::from_chars(first, last, i); ec == std::errc() && end == last)
                return static_cast<double>(i);
        }
        double v = 0;
        auto [end, ec] = std::from_chars(first, last, v);
        if (end != last || (ec != std::errc() && ec != std::errc::result_out_of_range))
            fail(quoted(w) + " is not a number");
        if (ec == std::errc::result_out_of_range)  // beyond double: infinite, or 0 below it
            v = std::strtod(std::string(first, last).c_str(), nullptr);
        return v;
    }
    int64_t integer(Type t) {
        double v = real(t);
        if (v != std::floor(v) || !(std::abs(v) < 9e15))
            fail(quoted(word_) + " is not a whole number");
        return static_cast<int64_t>(v);
    }
    uint64_t count(Type t, Type) {
        int64_t n = integer(t);
        if (n < 0) fail("a list count is negative (" + std::to_string(n) + ")");
        if (static_cast<uint64_t>(n) > remaining() / 2 + 1) truncated();
        return static_cast<uint64_t>(n);
    }
    void skip(Type) { word(); }
    void skipItems(uint64_t n, Type) {
        for (uint64_t i = 0; i < n; ++i) word();
    }

    /// Whether only blanks are left; if not, the next word is where they end.
    bool atEnd() {
        skipBlanks();
        return p_ == end_;
    }
    FileLoc here() const { return {file_, line_, static_cast<int>(p_ - lineStart_) + 1}; }

    [[noreturn]] void truncated() const {
        throw SceneError(here(), "the file ends in " + recordOfCount() + ": is it complete?");
    }
    [[noreturn]] void fail(const std::string& what) const {
        throw SceneError({file_, wordLine_, wordColumn_}, record() + ": " + what);
    }

  private:
    void skipBlanks() {
        while (p_ < end_) {
            char c = *p_;
            if (c == '\n') {
                ++line_;
                lineStart_ = p_ + 1;
            } else if (c != ' ' && c != '\t' && c != '\r' && c != '\v' && c != '\f') {
                break;
            }
            ++p_;
        }
    }
    std::string_view word() {
        skipBlanks();
        if (p_ == end_) truncated();
        const char* start = p_;
        wordLine_ = line_;
        wordColumn_ = static_cast<int>(start - lineStart_) + 1;
        while (p_ < end_ && *p_ != ' ' && *p_ != '\t' && *p_ != '\n' && *p_ != '\r' &&
               *p_ != '\v' && *p_ != '\f')
            ++p_;
        word_ = std::string_view(start, static_cast<size_t>(p_ - start));
        return word_;
    }

    const char* p_;
    const char* end_;
    const char* lineStart_;
    int line_;
    int wordLine_ = 0, wordColumn_ = 0;
    std::string_view word_;
    const std::string& file_;
};

}  // namespace glint::ply
