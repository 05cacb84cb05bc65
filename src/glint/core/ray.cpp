#include "glint/core/ray.h"

#include <ostream>

namespace glint {

std::ostream& operator<<(std::ostream& out, const Ray& r) {
    return out << "Ray{origin " << r.origin << ", dir " << r.dir << ", t [" << r.tMin << ", "
               << r.tMax << "]}";
}

std::ostream& operator<<(std::ostream& out, const Hit& h) {
    if (!(h.t < std::numeric_limits<float>::infinity())) return out << "Hit{none}";
    out << "Hit{t " << h.t << ", prim " << h.primId;
    if (h.subId != 0) out << ", sub " << h.subId;
    return out << '}';
}

}  // namespace glint
