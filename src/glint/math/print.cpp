// How the math types print themselves (operator<<, declared beside each type).

#include <ostream>

#include "glint/math/bbox.h"
#include "glint/math/mat4.h"
#include "glint/math/sampling.h"
#include "glint/math/transform.h"
#include "glint/math/vec3.h"

namespace glint {

std::ostream& operator<<(std::ostream& out, const Vec3& v) {
    return out << '(' << v.x << ", " << v.y << ", " << v.z << ')';
}

std::ostream& operator<<(std::ostream& out, const Vec3f& v) {
    return out << '(' << v.x << ", " << v.y << ", " << v.z << ')';
}

std::ostream& operator<<(std::ostream& out, const Point2& p) {
    return out << '(' << p.x << ", " << p.y << ')';
}

std::ostream& operator<<(std::ostream& out, const Bounds3f& b) {
    if (b.empty()) return out << "[empty]";
    return out << '[' << b.lo << " .. " << b.hi << ']';
}

namespace {

void printRows(std::ostream& out, const Mat4& m, int rows) {
    out << '[';
    for (int r = 0; r < rows; ++r) {
        out << (r ? ", [" : "[");
        for (int c = 0; c < 4; ++c) out << (c ? ", " : "") << m.m[r][c];
        out << ']';
    }
    out << ']';
}

}  // namespace

std::ostream& operator<<(std::ostream& out, const Mat4& m) {
    printRows(out, m, 4);
    return out;
}

std::ostream& operator<<(std::ostream& out, const Transform& t) {
    out << "Transform";
    printRows(out, t.matrix(), 3);
    return out;
}

}  // namespace glint
