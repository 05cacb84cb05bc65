#pragma once
// Shared by ply_header.cpp (the header) and ply_loader.cpp (the elements). Internal to
// glint/io: use ply_loader.h.

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "glint/core/error.h"

namespace glint::ply {

/// `text` in single quotes (built by appending: GCC 12 warns falsely on "'" + string).
inline std::string quoted(std::string_view text) {
    std::string q(1, '\'');
    q.append(text);
    q.push_back('\'');
    return q;
}

/// A warning about a whole file or a place in it (built in steps: GCC 12 warns falsely on the
/// aggregate).
inline Diagnostic warningAt(FileLoc loc, std::string message) {
    Diagnostic d;
    d.loc = std::move(loc);
    d.message = std::move(message);
    return d;
}

/// The scalar types of a PLY property.
enum class Type : uint8_t { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

/// Bytes of a value of type `t` in a binary file.
constexpr size_t typeSize(Type t) {
    switch (t) {
        case Type::Int8:
        case Type::UInt8:
            return 1;
        case Type::Int16:
        case Type::UInt16:
            return 2;
        case Type::Int32:
        case Type::UInt32:
        case Type::Float32:
            return 4;
        case Type::Float64:
            return 8;
    }
    return 1;
}

constexpr bool isInteger(Type t) { return t != Type::Float32 && t != Type::Float64; }

/// One `property` line: a scalar, or a list (`property list uchar int vertex_indices`).
struct Property {
    std::string name;
    Type type = Type::Float32;  ///< The scalar's type, or the type of a list's items.
    bool list = false;
    Type countType = Type::UInt8;  ///< A list's count.
};

/// One `element` line and its properties.
struct Element {
    std::string name;
    uint64_t count = 0;
    std::vector<Property> properties;
    int line = 0;  ///< Of its `element` line.

    bool hasList() const;
    /// Bytes of one record in a binary file without its lists' items: all of it when the
    /// element has no list.
    size_t fixedBytes() const;
    /// The index of property `name`, or -1.
    int find(std::string_view wanted) const;
};

enum class Format : uint8_t { Ascii, BinaryLittleEndian, BinaryBigEndian };

struct Header {
    Format format = Format::Ascii;
    std::vector<Element> elements;
    size_t dataOffset = 0;  ///< Where the elements start: just past the `end_header` line.
    int dataLine = 0;       ///< The line they start on (ASCII files).
};

/// What a property of the vertex or face element is to Glint: skipped; a position, normal,
/// colour or texture coordinate component (colours also per face); a face's `vertex_indices`
/// list; a face's per-corner texture coordinates (`texcoord`: u0 v0 u1 v1 ...).
enum Role : uint8_t {
    kSkip,
    kX,
    kY,
    kZ,
    kNx,
    kNy,
    kNz,
    kRed,
    kGreen,
    kBlue,
    kAlpha,
    kU,
    kV,
    kIndices,
    kTexcoord,
    kRoles  ///< How many there are.
};

/// The roles of one element's properties, and which groups of them are complete.
struct Layout {
    std::vector<Role> roles;  ///< Per property.
    bool normals = false, colors = false, alpha = false, uvs = false;
    int indices = -1, texcoord = -1;  ///< Face lists (property numbers), -1: none.
};

/// The roles of the vertex element's properties. Throws SceneError at the element's line if it
/// lacks x, y or z.
Layout vertexLayout(const Element& e, const std::string& file);
/// The roles of a face (or tristrips) element's properties: its index list, per-corner texture
/// coordinates and face colours. Throws SceneError at the element's line if it has no
/// `vertex_indices` list of integers.
Layout faceLayout(const Element& e, const std::string& file);

/// `v` as a float: beyond float's range, infinite (as IEEE rounding would give, stated).
float toFloat(double v);
/// A colour channel of type `t` as a fraction in [0, 1] (NaN as 0), sRGB-decoded unless alpha.
float colourChannel(double v, Type t, bool alpha);

/// Reads the header of the PLY file `bytes`. Throws SceneError at `file`:line:column for what it
/// does not understand (a missing `ply` or `format` line, an unknown type or keyword, a count
/// that is not a number, no `end_header`).
Header parseHeader(std::string_view bytes, const std::string& file);

}  // namespace glint::ply
