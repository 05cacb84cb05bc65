#include "glint/render/lights/light.h"

#include <ostream>

namespace glint {

Light lightFromSpec(const LightSpec& s) {
    switch (s.kind) {
        case LightSpec::Kind::Point:
            return PointLight{s.position, s.color, s.attenuation, s.range};
        case LightSpec::Kind::Spot:
            return SpotLight{s.position, s.axis,     s.color, s.attenuation,
                             s.cosInner, s.cosOuter, s.range};
        case LightSpec::Kind::Directional:
            return DirectionalLight{s.direction, s.color};
        case LightSpec::Kind::Quad:
            break;
    }
    return QuadLight{s.position, s.edge1, s.edge2, s.color};
}

std::ostream& operator<<(std::ostream& out, const Light& light) {
    std::visit([&](const auto& l) { out << l; }, light.light_);
    return out;
}

std::ostream& operator<<(std::ostream& out, const LightLiSample& s) {
    out << "LightLiSample{wi " << s.wi << ", L " << s.L << ", pdf " << s.pdf << ", distance "
        << s.distance;
    if (s.delta) out << ", delta";
    return out << "}";
}

std::ostream& operator<<(std::ostream& out, const LightLeSample& s) {
    out << "LightLeSample{" << s.ray << ", L " << s.L << ", beta " << s.beta << ", pdfPos "
        << s.pdfPos << ", pdfDir " << s.pdfDir;
    if (s.attenuation) out << ", attenuation " << *s.attenuation;
    return out << "}";
}

}  // namespace glint
