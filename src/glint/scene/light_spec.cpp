#include "glint/scene/light_spec.h"

#include <ostream>

namespace glint {

std::ostream& operator<<(std::ostream& out, const LightSpec& l) {
    out << "LightSpec{";
    switch (l.kind) {
        case LightSpec::Kind::Point:
            out << "point at " << l.position << ", colour " << l.color << ", attenuation "
                << l.attenuation;
            break;
        case LightSpec::Kind::Spot:
            out << "spot at " << l.position << " along " << l.axis << ", colour " << l.color
                << ", attenuation " << l.attenuation << ", cos inner " << l.cosInner
                << ", cos outer " << l.cosOuter;
            break;
        case LightSpec::Kind::Directional:
            out << "directional towards " << l.direction << ", colour " << l.color;
            break;
        case LightSpec::Kind::Quad:
            out << "quad at " << l.position << ", edges " << l.edge1 << " and " << l.edge2
                << ", radiance " << l.color;
            break;
    }
    return out << "}";
}

}  // namespace glint
