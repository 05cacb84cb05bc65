// The header of a PLY file: its format, and the elements and properties that follow it
// (http://paulbourke.net/dataformats/ply/, Greg Turk's description of the format).

#include <charconv>
#include <optional>

#include "glint/io/ply/ply_internal.h"

namespace glint::ply {

bool Element::hasList() const {
    for (const Property& p : properties)
        if (p.list) return true;
    return false;
}

size_t Element::fixedBytes() const {
    size_t n = 0;
    for (const Property& p : properties) n += typeSize(p.list ? p.countType : p.type);
    return n;
}

int Element::find(std::string_view wanted) const {
    for (size_t i = 0; i < properties.size(); ++i)
        if (properties[i].name == wanted) return static_cast<int>(i);
    return -1;
}

namespace {

/// A word of a header line and its column (1-based).
struct Word {
    std::string_view text;
    int column = 0;
};

std::vector<Word> words(std::string_view line) {
    std::vector<Word> out;
    size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
        size_t start = i;
        while (i < line.size() && line[i] != ' ' && line[i] != '\t') ++i;
        if (i > start) out.push_back({line.substr(start, i - start), static_cast<int>(start) + 1});
    }
    return out;
}

std::optional<Type> typeNamed(std::string_view name) {
    struct Named {
        std::string_view name;
        Type type;
    };
    static constexpr Named kTypes[] = {
        {"char", Type::Int8},       {"int8", Type::Int8},       {"uchar", Type::UInt8},
        {"uint8", Type::UInt8},     {"short", Type::Int16},     {"int16", Type::Int16},
        {"ushort", Type::UInt16},   {"uint16", Type::UInt16},   {"int", Type::Int32},
        {"int32", Type::Int32},     {"uint", Type::UInt32},     {"uint32", Type::UInt32},
        {"float", Type::Float32},   {"float32", Type::Float32}, {"double", Type::Float64},
        {"float64", Type::Float64},
    };
    for (const Named& t : kTypes)
        if (t.name == name) return t.type;
    return std::nullopt;
}

[[noreturn]] void failAt(const std::string& file, int line, int column,
                         const std::string& message) {
    throw SceneError({file, line, column}, message);
}

constexpr const char* kTypeList =
    "char, uchar, short, ushort, int, uint, float, double, or int8 to float64";

}  // namespace

Header parseHeader(std::string_view bytes, const std::string& file) {
    Header h;
    size_t pos = 0;
    int lineNo = 0;
    bool sawFormat = false;
    auto fail = [&](int column, const std::string& message) {
        failAt(file, lineNo, column, message);
    };
    while (true) {
        if (pos >= bytes.size())
            throw SceneError({file, lineNo, 0},
                             "the PLY header has no 'end_header' line: is the file complete?");
        size_t eol = bytes.find('\n', pos);
        size_t next = eol == std::string_view::npos ? bytes.size() : eol + 1;
        std::string_view line = bytes.substr(pos, next - pos);
        if (!line.empty() && line.back() == '\n') line.remove_suffix(1);
        if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
        pos = next;
        ++lineNo;
        std::vector<Word> w = words(line);
        if (lineNo == 1) {
            if (w.size() != 1 || w[0].text != "ply" || w[0].column != 1)
                fail(1, "not a PLY file: the first line must be 'ply'");
            continue;
        }
        if (w.empty()) continue;
        std::string_view key = w[0].text;
        if (key == "comment" || key == "obj_info") continue;
        if (key == "end_header") {
            if (eol == std::string_view::npos)
                fail(w[0].column,
                     "the PLY header ends without a line break: is the file complete?");
            break;
        }
        if (key == "format") {
            if (sawFormat) fail(w[0].column, "a second 'format' line");
            if (w.size() < 2)
                fail(w[0].column,
                     "'format' needs ascii, binary_little_endian or binary_big_endian");
            if (w[1].text == "ascii")
                h.format = Format::Ascii;
            else if (w[1].text == "binary_little_endian")
                h.format = Format::BinaryLittleEndian;
            else if (w[1].text == "binary_big_endian")
                h.format = Format::BinaryBigEndian;
            else
                fail(w[1].column, "unknown PLY format '" + std::string(w[1].text) +
                                      "' (ascii, binary_little_endian or binary_big_endian)");
            if (w.size() >= 3 && w[2].text != "1.0")
                fail(w[2].column,
                     "PLY version '" + std::string(w[2].text) + "' is not 1.0, the only one");
            sawFormat = true;
        } else if (key == "element") {
            if (!sawFormat) fail(w[0].column, "'element' before the 'format' line");
            if (w.size() != 3) fail(w[0].column, "'element' expects a name and a count");
            Element e;
            e.name = std::string(w[1].text);
            e.line = lineNo;
            std::string_view c = w[2].text;
            auto [end, ec] = std::from_chars(c.data(), c.data() + c.size(), e.count);
            if (ec != std::errc() || end != c.data() + c.size())
                fail(w[2].column, "element count '" + std::string(c) +
                                      "' is not a whole number of at most 2^64 - 1");
            h.elements.push_back(std::move(e));
        } else if (key == "property") {
            if (h.elements.empty()) fail(w[0].column, "'property' before any 'element'");
            Property p;
            size_t k = 1;
            if (w.size() >= 2 && w[1].text == "list") {
                if (w.size() != 5)
                    fail(w[0].column,
                         "'property list' expects a count type, an item type and "
                         "a name");
                std::optional<Type> count = typeNamed(w[2].text);
                if (!count || !isInteger(*count))
                    fail(w[2].column, "a list's count type must be an integer type, got '" +
                                          std::string(w[2].text) + "'");
                p.list = true;
                p.countType = *count;
                k = 3;
            } else if (w.size() != 3) {
                fail(w[0].column, "'property' expects a type and a name");
            }
            std::optional<Type> type = typeNamed(w[k].text);
            if (!type)
                fail(w[k].column,
                     "unknown PLY type '" + std::string(w[k].text) + "' (" + kTypeList + ")");
            p.type = *type;
            p.name = std::string(w[k + 1].text);
            h.elements.back().properties.push_back(std::move(p));
        } else {
            fail(w[0].column, "unknown PLY header line '" + std::string(key) +
                                  "' (format, element, property, comment, obj_info or end_header)");
        }
    }
    if (!sawFormat) throw SceneError({file, lineNo, 0}, "the PLY header has no 'format' line");
    h.dataOffset = pos;
    h.dataLine = lineNo + 1;
    return h;
}

}  // namespace glint::ply
