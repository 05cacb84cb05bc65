#include "glint/render/lights/directional_light.h"

#include <ostream>

#include "glint/render/lights/light_util.h"

namespace glint {

using namespace light_util;

double DirectionalLight::pdfLi(const Vec3&, const LightPoint&, double) const { return 0; }

std::optional<LightLeSample> DirectionalLight::sampleLe(Point2 uPos, Point2,
                                                        const LightLeContext& ctx) const {
    return acrossDisc(direction, color, 1, uPos, ctx);
}

LightLePdf DirectionalLight::pdfLe(const Vec3&, const Vec3&, const Vec3&,
                                   const LightLeContext& ctx) const {
    return {1 / (kPi * ctx.radius * ctx.radius), 0};
}

double DirectionalLight::infiniteImportance() const { return kPi * brightness(color); }

std::ostream& operator<<(std::ostream& out, const DirectionalLight& l) {
    return out << "DirectionalLight{towards " << l.direction << ", colour " << l.color << "}";
}

}  // namespace glint
