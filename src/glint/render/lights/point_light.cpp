#include "glint/render/lights/point_light.h"

#include <algorithm>
#include <cmath>
#include <ostream>

#include "glint/render/lights/light_util.h"
#include "glint/scene/light_spec.h"

namespace glint {

using namespace light_util;

double PointLight::pdfLi(const Vec3&, const LightPoint&, double) const { return 0; }

std::optional<LightLeSample> PointLight::sampleLe(Point2, Point2 uDir,
                                                  const LightLeContext& ctx) const {
    const auto [dir, pdf] = sampleTowardsSphere(position, ctx.center, ctx.radius, uDir);
    return LightLeSample{Ray{position, dir, 0, kInfinity},
                         position,
                         Vec3(0),
                         intensity,
                         intensity / pdf,
                         1,
                         pdf,
                         attenuation};
}

LightLePdf PointLight::pdfLe(const Vec3&, const Vec3&, const Vec3& dir,
                             const LightLeContext& ctx) const {
    return {0, pdfTowardsSphere(position, ctx.center, ctx.radius, dir)};
}

std::optional<LightBounds> PointLight::bounds() const {
    // Its power, estimated at unit distance.
    const double att = std::max(attenuation.x + attenuation.y + attenuation.z, 1e-6);
    const double power = 4 * kPi * brightness(intensity) / att;
    if (!(power > 0)) return std::nullopt;
    return LightBounds::point(position, power);
}

std::ostream& operator<<(std::ostream& out, const PointLight& l) {
    out << "PointLight{at " << l.position << ", intensity " << l.intensity << ", attenuation "
        << l.attenuation;
    if (l.range > 0) out << ", range " << l.range;
    return out << "}";
}

}  // namespace glint
