// What Glint reads of a PLY file's vertex and face properties (docs/scene-format.md, "PLY and
// STL files"): their names, the groups they form, and how colours and numbers are converted.

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <string_view>

#include "glint/io/ply/ply_internal.h"
#include "glint/scene/texture.h"

namespace glint::ply {
namespace {

Role vertexRole(std::string_view name) {
    struct Named {
        std::string_view name;
        Role role;
    };
    static constexpr Named kNames[] = {
        {"x", kX},
        {"y", kY},
        {"z", kZ},
        {"nx", kNx},
        {"ny", kNy},
        {"nz", kNz},
        {"normal_x", kNx},
        {"normal_y", kNy},
        {"normal_z", kNz},
        {"red", kRed},
        {"green", kGreen},
        {"blue", kBlue},
        {"alpha", kAlpha},
        {"diffuse_red", kRed},
        {"diffuse_green", kGreen},
        {"diffuse_blue", kBlue},
        {"s", kU},
        {"t", kV},
        {"u", kU},
        {"v", kV},
        {"texture_u", kU},
        {"texture_v", kV},
        {"texture_s", kU},
        {"texture_t", kV},
    };
    for (const Named& n : kNames)
        if (n.name == name) return n.role;
    return kSkip;
}

/// The largest value of an integer type: colours of integer types are fractions of it.

double integerMax(Type t) {
    switch (t) {
        case Type::Int8:
            return 127;
        case Type::UInt8:
            return 255;
        case Type::Int16:
            return 32767;
        case Type::UInt16:
            return 65535;
        case Type::Int32:
            return 2147483647.0;
        case Type::UInt32:
            return 4294967295.0;
        default:
            return 1;
    }
}

/// Assigns `role` to property `i` unless an earlier property has it (then it is skipped).

void assign(Layout& l, size_t i, Role role, std::array<bool, kRoles>& taken) {
    if (role == kSkip || taken[role]) return;
    l.roles[i] = role;
    taken[role] = true;
}

void completeGroups(Layout& l, const std::array<bool, kRoles>& taken) {
    l.normals = taken[kNx] && taken[kNy] && taken[kNz];
    l.colors = taken[kRed] && taken[kGreen] && taken[kBlue];
    l.alpha = l.colors && taken[kAlpha];
    l.uvs = taken[kU] && taken[kV];
    for (Role& r : l.roles) {  // parts of incomplete groups are skipped
        if ((r == kNx || r == kNy || r == kNz) && !l.normals) r = kSkip;
        if ((r == kRed || r == kGreen || r == kBlue || r == kAlpha) && !l.colors) r = kSkip;
        if ((r == kU || r == kV) && !l.uvs) r = kSkip;
    }
}

[[noreturn]] void failAt(const std::string& file, const Element& e, const std::string& message) {
    throw SceneError({file, e.line, 0}, message);
}

/// The sRGB transfer function's inverse (IEC 61966-2-1) for `c` in [0, 1].
double srgbDecode(double c) {
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

}  // namespace

Layout vertexLayout(const Element& e, const std::string& file) {
    Layout l;
    l.roles.assign(e.properties.size(), kSkip);
    std::array<bool, kRoles> taken{};
    for (size_t i = 0; i < e.properties.size(); ++i)
        if (!e.properties[i].list) assign(l, i, vertexRole(e.properties[i].name), taken);
    if (!taken[kX] || !taken[kY] || !taken[kZ])
        failAt(file, e, "element 'vertex' needs properties 'x', 'y' and 'z' (scalars)");
    completeGroups(l, taken);
    return l;
}

Layout faceLayout(const Element& e, const std::string& file) {
    Layout l;
    l.roles.assign(e.properties.size(), kSkip);
    std::array<bool, kRoles> taken{};
    for (size_t i = 0; i < e.properties.size(); ++i) {
        const Property& p = e.properties[i];
        if (p.name == "vertex_indices" || p.name == "vertex_index") {
            if (l.indices >= 0) continue;
            if (!p.list || !isInteger(p.type))
                failAt(file, e,
                       "element '" + e.name + "': property '" + p.name +
                           "' must be a list of integers ('property list uchar int " + p.name +
                           "')");
            l.indices = static_cast<int>(i);
            l.roles[i] = kIndices;
        } else if (p.name == "texcoord" && p.list) {
            if (l.texcoord < 0) l.texcoord = static_cast<int>(i), l.roles[i] = kTexcoord;
        } else if (!p.list) {
            Role r = vertexRole(p.name);
            if (r >= kRed && r <= kAlpha) assign(l, i, r, taken);
        }
    }
    if (l.indices < 0) failAt(file, e, "element '" + e.name + "' has no 'vertex_indices' list");
    completeGroups(l, taken);
    return l;
}

float toFloat(double v) {
    constexpr double kMax = std::numeric_limits<float>::max();
    if (std::abs(v) <= kMax) return static_cast<float>(v);
    return std::isnan(v) ? std::numeric_limits<float>::quiet_NaN()
                         : std::copysign(std::numeric_limits<float>::infinity(),
                                         static_cast<float>(v > 0 ? 1 : -1));
}

float colourChannel(double v, Type t, bool alpha) {
    if (t == Type::UInt8 && !alpha && v >= 0 && v <= 255 && v == std::floor(v))
        return static_cast<float>(srgbToLinear(static_cast<uint8_t>(v)));
    double f = isInteger(t) ? v / integerMax(t) : v;
    f = f >= 0 ? std::min(f, 1.0) : 0.0;
    return static_cast<float>(alpha ? f : srgbDecode(f));
}

}  // namespace glint::ply
