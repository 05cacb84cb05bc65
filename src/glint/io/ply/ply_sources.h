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

#include "glint/core/parse_float.h"
#include "glint/io/ply/ply_internal.h"

namespace glint::ply {

/// A strip's end (-1 in a `tristrips` list).
constexpr uint32_t kNoIndex = UINT32_MAX;

/// Why vertex index `x` is not one of `vertices`.
inline std::string indexProblem(int64_t x, uint64_t vertices) {
    return "vertex index " + std::to_string(x) + " is out of range: the file has " +
           std::to_string(vertices) + " vertices (0 to " + std::to_string(vertices) + " - 1)";
}

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
        double v = valueAt(t, p_);
        last_ = p_;
        p_ += n;
        return v;
    }
    /// A value of an integer type.
    int64_t integer(Type t) {
        if (remaining() < typeSize(t)) truncated();
        int64_t v = integerAt(t, p_);
        last_ = p_;
        p_ += typeSize(t);
        return v;
    }
    /// A list's count: not negative, and no more items of `item` than the bytes left hold.
    uint64_t count(Type t, Type item) {
        int64_t n = integer(t);
        if (n < 0) fail("a list count is negative (" + std::to_string(n) + ")");
        if (static_cast<uint64_t>(n) > remaining() / typeSize(item)) truncated();
        return static_cast<uint64_t>(n);
    }
    /// The `n` vertex indices of type `t` of a list whose count() was just read, each below
    /// `vertices` (or -1 where `strips`: stored as kNoIndex).
    void indices(Type t, uint64_t n, uint32_t* out, uint64_t vertices, bool strips) {
        const size_t size = typeSize(t);
        if (n > remaining() / size) truncated();
        for (uint64_t k = 0; k < n; ++k, p_ += size) {
            int64_t x = integerAt(t, p_);
            if (x >= 0 && static_cast<uint64_t>(x) < vertices) {
                out[k] = static_cast<uint32_t>(x);
            } else if (strips && x == -1) {
                out[k] = kNoIndex;
            } else {
                last_ = p_;
                fail(indexProblem(x, vertices));
            }
        }
    }
    /// The next `n` bytes, a record of fixed size whose values valueAt() reads; errors about
    /// it point at its start.
    const unsigned char* fixedRecord(size_t n) {
        if (remaining() < n) truncated();
        last_ = p_;
        p_ += n;
        return last_;
    }
    /// The value of type `t` at `q`, as a double.
    double valueAt(Type t, const unsigned char* q) const {
        switch (t) {
            case Type::Float32:
                return load<float>(q);
            case Type::Float64:
                return load<double>(q);
            default:
                return static_cast<double>(integerAt(t, q));
        }
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
    T load(const unsigned char* q) const {
        std::array<unsigned char, sizeof(T)> b;
        std::memcpy(b.data(), q, sizeof(T));
        if (swap_) std::reverse(b.begin(), b.end());
        T v;
        std::memcpy(&v, b.data(), sizeof(T));
        return v;
    }
    /// An integer type's value at `q`; a float type's if it is a whole number below 2^53 in
    /// magnitude, else -1.
    int64_t integerAt(Type t, const unsigned char* q) const {
        switch (t) {
            case Type::Int8:
                return load<int8_t>(q);
            case Type::UInt8:
                return load<uint8_t>(q);
            case Type::Int16:
                return load<int16_t>(q);
            case Type::UInt16:
                return load<uint16_t>(q);
            case Type::Int32:
                return load<int32_t>(q);
            case Type::UInt32:
                return load<uint32_t>(q);
            case Type::Float32:
            case Type::Float64: {
                double v = t == Type::Float32 ? load<float>(q) : load<double>(q);
                return v == std::floor(v) && std::abs(v) < 9e15 ? static_cast<int64_t>(v) : -1;
            }
        }
        return -1;
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
        // The common case at once: a number that ends at a blank.
        skipBlanks();
        wordLine_ = line_;
        wordColumn_ = static_cast<int>(p_ - lineStart_) + 1;
        if (isInteger(t)) {
            int64_t i = 0;
            auto [stop, code] = std::from_chars(p_, end_, i);
            if (code == std::errc() && (stop == end_ || isBlank(*stop))) {
                word_ = std::string_view(p_, static_cast<size_t>(stop - p_));
                p_ = stop;
                return static_cast<double>(i);
            }
        } else if (t == Type::Float32) {  // read as a float: rounded once
            float f = 0;
            auto [stop, code] = parseFloat(p_, end_, f);
            if (code == std::errc() && (stop == end_ || isBlank(*stop))) {
                word_ = std::string_view(p_, static_cast<size_t>(stop - p_));
                p_ = stop;
                return f;
            }
        } else {
            double v = 0;
            auto [stop, code] = parseFloat(p_, end_, v);
            if (code == std::errc() && (stop == end_ || isBlank(*stop))) {
                word_ = std::string_view(p_, static_cast<size_t>(stop - p_));
                p_ = stop;
                return v;
            }
        }
        // Otherwise the word, and what it is (or what is wrong with it).
        std::string_view w = word();
        const char* first = w.data() + (w.size() > 1 && w[0] == '+');
        const char* last = w.data() + w.size();
        if (isInteger(t)) {
            int64_t i = 0;
            if (auto [end, ec] = std::from_chars(first, last, i); ec == std::errc() && end == last)
                return static_cast<double>(i);
        }
        double v = 0;
        auto [end, ec] = parseFloat(first, last, v);
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
    void indices(Type t, uint64_t n, uint32_t* out, uint64_t vertices, bool strips) {
        for (uint64_t k = 0; k < n; ++k) {
            int64_t x = integer(t);
            if (x >= 0 && static_cast<uint64_t>(x) < vertices)
                out[k] = static_cast<uint32_t>(x);
            else if (strips && x == -1)
                out[k] = kNoIndex;
            else
                fail(indexProblem(x, vertices));
        }
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
    static bool isBlank(char c) { return c == ' ' || (c >= '\t' && c <= '\r'); }
    void skipBlanks() {
        const char* p = p_;  // a local: stores through char pointers would reload members
        while (p < end_ && isBlank(*p)) {
            if (*p == '\n') {
                ++line_;
                lineStart_ = p + 1;
            }
            ++p;
        }
        p_ = p;
    }
    std::string_view word() {
        skipBlanks();
        if (p_ == end_) truncated();
        const char* start = p_;
        wordLine_ = line_;
        wordColumn_ = static_cast<int>(start - lineStart_) + 1;
        const char* p = start;
        while (p < end_ && !isBlank(*p)) ++p;
        p_ = p;
        word_ = std::string_view(start, static_cast<size_t>(p - start));
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
