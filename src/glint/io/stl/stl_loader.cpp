// STL meshes: binary (an 80-byte header, a little-endian triangle count, then per triangle a
// normal, three corners and two attribute bytes: 50 bytes) and ASCII (solid / facet normal /
// outer loop / vertex ... / endloop / endfacet / endsolid).

#include "glint/io/stl/stl_loader.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <system_error>

#include "glint/core/mapped_file.h"
#include "glint/core/parse_float.h"
#include "glint/io/mesh_memory.h"
#include "glint/math/bits.h"

namespace glint {
namespace stl {
namespace {

/// `text` in single quotes (built by appending: GCC 12 warns falsely on "'" + string).
std::string quoted(std::string_view text) {
    std::string q(1, '\'');
    q.append(text);
    q.push_back('\'');
    return q;
}

/// A warning (built in steps: GCC 12 warns falsely on the aggregate).
Diagnostic warningAt(FileLoc loc, std::string message) {
    Diagnostic d;
    d.loc = std::move(loc);
    d.message = std::move(message);
    return d;
}

/// Blanks and line breaks (what std::isspace says in the C locale, without its call per byte).
constexpr bool isBlank(char c) { return c == ' ' || (c >= '\t' && c <= '\r'); }

constexpr char lower(char c) { return c >= 'A' && c <= 'Z' ? static_cast<char>(c + 32) : c; }

uint32_t loadU32(const unsigned char* p) {
    return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
}

float loadF32(const unsigned char* p) { return bitCast<float>(loadU32(p)); }

/// Whether the file is ASCII STL: it starts with the word `solid` (after blanks) and its first
/// bytes hold no control character a text file would not.
bool isAscii(std::string_view bytes) {
    std::string_view head = bytes.substr(0, 512);
    size_t i = head.find_first_not_of(" \t\r\n");
    if (i == std::string_view::npos || head.size() - i < 5) return false;
    for (size_t k = 0; k < 5; ++k)
        if (lower(head[i + k]) != "solid"[k]) return false;
    if (head.size() > i + 5 && !isBlank(head[i + 5])) return false;
    for (char ch : head) {
        unsigned char c = static_cast<unsigned char>(ch);
        if ((c < 0x20 && !(c >= '\t' && c <= '\r')) || c == 0x7F) return false;
    }
    return true;
}

/// Adds the corner positions of one triangle (three new vertices).
void addTriangle(MeshData& mesh, const std::array<Vec3f, 3>& p) {
    MeshData::Triangle t;
    for (size_t k = 0; k < 3; ++k) {
        t.corners[k].position = static_cast<uint32_t>(mesh.positions.size());
        mesh.positions.push_back(p[k]);
    }
    mesh.triangles.push_back(t);
}

MeshData parseBinary(std::string_view bytes, const std::string& file,
                     std::vector<Diagnostic>& warnings, const LoadLimits& limits) {
    const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
    const uint64_t count = loadU32(data + 80);
    const uint64_t expected = binaryStlBytes(count);
    if (bytes.size() < expected)
        throw SceneError({file, 0, 0}, "the binary STL header announces " + std::to_string(count) +
                                           " triangles (" + std::to_string(expected) +
                                           " bytes), but the file has " +
                                           std::to_string(bytes.size()) +
                                           " bytes: is it complete?");
    if (bytes.size() > expected)
        warnings.push_back(
            warningAt({file, 0, 0}, std::to_string(bytes.size() - expected) +
                                        " bytes follow the last of the " + std::to_string(count) +
                                        " triangles the header announces: they are ignored"));
    if (3 * count >= MeshData::kNone)
        throw SceneError({file, 0, 0}, "more triangles than Glint can index");
    MeshCounts counts;
    counts.positions = 3 * double(count);
    counts.triangles = double(count);
    checkMeshMemory(counts, file, limits);

    MeshData mesh;
    mesh.name = file;
    mesh.positions.reserve(static_cast<size_t>(3 * count));  // within the memory checked above
    mesh.triangles.reserve(static_cast<size_t>(count));
    for (uint64_t i = 0; i < count; ++i) {
        const unsigned char* t = data + 84 + 50 * i + 12;  // past the facet normal
        std::array<Vec3f, 3> p;
        for (size_t k = 0; k < 3; ++k) {
            p[k] = Vec3f(loadF32(t + 12 * k), loadF32(t + 12 * k + 4), loadF32(t + 12 * k + 8));
            if (!std::isfinite(p[k].x) || !std::isfinite(p[k].y) || !std::isfinite(p[k].z))
                throw SceneError({file, 0, 0}, "triangle " + std::to_string(i) + " (byte " +
                                                   std::to_string(84 + 50 * i + 12 + 12 * k) +
                                                   "): vertex coordinates must be finite numbers");
        }
        addTriangle(mesh, p);
    }
    if (count == 0) throw SceneError({file, 0, 0}, "the binary STL file has no triangles");
    return mesh;
}

/// ASCII STL, word by word: keywords in any case, each name after `solid` and `endsolid` to
/// the end of its line.
class AsciiReader {
  public:
    AsciiReader(std::string_view bytes, const std::string& file, std::vector<Diagnostic>& warnings)
        : p_(bytes.data()),
          end_(p_ + bytes.size()),
          lineStart_(p_),
          file_(file),
          warnings_(warnings) {
        mesh_.name = file;
    }

    MeshData run(const LoadLimits& limits);

  private:
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
    /// The next word ("" at the end of the file), and where it starts.
    std::string_view word() {
        skipBlanks();
        const char* start = p_;
        wordLine_ = line_;  // not a FileLoc: no copy of the file name per word
        wordColumn_ = static_cast<int>(start - lineStart_) + 1;
        const char* p = start;
        while (p < end_ && !isBlank(*p)) ++p;
        p_ = p;
        return {start, static_cast<size_t>(p - start)};
    }
    static bool is(std::string_view w, std::string_view keyword) {
        if (w.size() != keyword.size()) return false;
        for (size_t i = 0; i < w.size(); ++i)
            if (lower(w[i]) != keyword[i]) return false;
        return true;
    }
    /// Whether the next word is `keyword` (in any case; consumed if so).
    bool accept(std::string_view keyword) {
        skipBlanks();
        const size_t n = keyword.size();
        if (static_cast<size_t>(end_ - p_) < n ||
            (static_cast<size_t>(end_ - p_) > n && !isBlank(p_[n])))
            return false;
        for (size_t i = 0; i < n; ++i)
            if (lower(p_[i]) != keyword[i]) return false;
        wordLine_ = line_;
        wordColumn_ = static_cast<int>(p_ - lineStart_) + 1;
        p_ += n;
        return true;
    }
    void expect(std::string_view keyword, const char* context) {
        if (accept(keyword)) return;
        std::string_view w = word();
        fail((w.empty() ? std::string("the file ends") : quoted(w)) + " where '" +
             std::string(keyword) + "' " + context + " should be" +
             (w.empty() ? ": is it complete?" : ""));
    }
    float number() {
        // The common case at once: a number that ends at a blank, within the float range
        // (read as a float: rounded once).
        skipBlanks();
        wordLine_ = line_;
        wordColumn_ = static_cast<int>(p_ - lineStart_) + 1;
        float f = 0;
        auto [stop, code] = parseFloat(p_, end_, f);
        if (code == std::errc() && (stop == end_ || isBlank(*stop)) && std::isfinite(f)) {
            p_ = stop;
            return f;
        }
        double v = 0;
        // Otherwise the word, and what is wrong with it (or a leading '+').
        std::string_view w = word();
        if (w.empty()) fail("the file ends where a number should be: is it complete?");
        const char* first = w.data() + (w.size() > 1 && w[0] == '+');
        auto [end, ec] = parseFloat(first, w.data() + w.size(), v);
        if (end != w.data() + w.size() ||
            (ec != std::errc() && ec != std::errc::result_out_of_range))
            fail(quoted(w) + " is not a number");
        if (ec == std::errc::result_out_of_range) v = std::strtod(std::string(w).c_str(), nullptr);
        if (!(std::abs(v) <= std::numeric_limits<float>::max()))
            fail(quoted(w) + ": coordinates must be finite numbers (at most about 3.4e38)");
        return static_cast<float>(v);
    }
    void skipLine() {
        while (p_ < end_ && *p_ != '\n') ++p_;
    }
    [[noreturn]] void fail(const std::string& message) const {
        throw SceneError(wordLoc(), message);
    }

    const char* p_;
    const char* end_;
    const char* lineStart_;
    int line_ = 1;
    FileLoc wordLoc() const { return {file_, wordLine_, wordColumn_}; }
    int wordLine_ = 0, wordColumn_ = 0;  ///< Where the last word read starts.
    const std::string& file_;
    std::vector<Diagnostic>& warnings_;
    MeshData mesh_;
    std::vector<Vec3f> loop_;  ///< The corners of the facet being read.
};

MeshData AsciiReader::run(const LoadLimits& limits) {
    expect("solid", "(the start of an ASCII STL file)");
    skipLine();  // the solid's name
    size_t bigFacets = 0;
    while (true) {
        std::string_view w = word();
        if (w.empty()) {
            warnings_.push_back(
                warningAt(wordLoc(), "the file ends without 'endsolid': is it complete?"));
            break;
        }
        if (is(w, "endsolid")) {
            skipLine();
            if (accept("solid")) {  // another solid follows
                skipLine();
                continue;
            }
            if (!word().empty()) fail("only another 'solid' may follow 'endsolid'");
            break;
        }
        if (!is(w, "facet")) fail(quoted(w) + " where 'facet' or 'endsolid' should be");
        const int facetLine = wordLine_, facetColumn = wordColumn_;
        expect("normal", "(after 'facet')");
        for (int k = 0; k < 3; ++k) number();  // the normal: not used
        expect("outer", "(of 'outer loop')");
        expect("loop", "(of 'outer loop')");
        loop_.clear();
        while (accept("vertex")) {
            float x = number(), y = number(), z = number();
            loop_.push_back(Vec3f(x, y, z));
        }
        expect("endloop", "(after a facet's vertices)");
        expect("endfacet", "(after 'endloop')");
        if (loop_.size() < 3)
            throw SceneError({file_, facetLine, facetColumn},
                             "a facet needs 3 vertices, got " + std::to_string(loop_.size()));
        if (loop_.size() > 3) ++bigFacets;
        if (mesh_.positions.size() + 3 * (loop_.size() - 2) >= MeshData::kNone)
            throw SceneError({file_, facetLine, facetColumn},
                             "more triangles than Glint can index");
        for (size_t k = 1; k + 1 < loop_.size(); ++k)
            addTriangle(mesh_, {loop_[0], loop_[k], loop_[k + 1]});
    }
    if (mesh_.triangles.empty()) throw SceneError({file_, 0, 0}, "the STL file has no facets");
    if (bigFacets > 0)
        warnings_.push_back(warningAt({file_, 0, 0}, std::to_string(bigFacets) +
                                                         " facets have more than 3 vertices: they "
                                                         "are split as fans"));
    MeshCounts counts;
    counts.positions = double(mesh_.positions.size());
    counts.triangles = double(mesh_.triangles.size());
    checkMeshMemory(counts, file_, limits);
    return std::move(mesh_);
}

}  // namespace
}  // namespace stl

MeshData parseStl(std::string_view bytes, const std::string& fileName,
                  std::vector<Diagnostic>& warnings, const StlOptions& options) {
    // A binary file's size is exactly what its count says; no ASCII file's can be: the count's
    // bytes would be text (at least 0x09 each), 150 million triangles or more, beyond the
    // largest file Glint reads.
    if (bytes.size() >= 84 &&
        bytes.size() ==
            binaryStlBytes(stl::loadU32(reinterpret_cast<const unsigned char*>(bytes.data()) + 80)))
        return stl::parseBinary(bytes, fileName, warnings, options.limits);
    if (stl::isAscii(bytes)) return stl::AsciiReader(bytes, fileName, warnings).run(options.limits);
    if (bytes.size() >= 84) return stl::parseBinary(bytes, fileName, warnings, options.limits);
    throw SceneError({fileName, 0, 0},
                     "not an STL file: too short for a binary one (" +
                         std::to_string(bytes.size()) +
                         " bytes, at least 84) and not text starting with 'solid'");
}

MeshData loadStl(const std::string& path, std::vector<Diagnostic>& warnings,
                 const StlOptions& options) {
    if (std::string problem = inputFileProblem(path); !problem.empty())
        throw SceneError({path, 0, 0}, "cannot read STL: " + problem);
    try {
        MappedFile file(path);
        return parseStl(file.text(), path, warnings, options);
    } catch (const std::system_error& e) {
        throw SceneError({path, 0, 0},
                         std::string("cannot read STL: ") + std::strerror(e.code().value()));
    }
}

}  // namespace glint
