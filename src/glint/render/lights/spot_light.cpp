#include "glint/render/lights/spot_light.h"

#include <algorithm>
#include <cmath>
#include <ostream>

#include "glint/render/lights/light_util.h"
#include "glint/scene/light_spec.h"

namespace glint {

using namespace light_util;

double SpotLight::falloff(const Vec3& w) const {
    // KHR_lights_punctual's implementation note: a linear ramp in the cosine, squared.
    const double ramp = (dot(w, axis) - cosOuter) / std::max(1e-3, cosInner - cosOuter);
    const double t = std::clamp(ramp, 0.0, 1.0);
    return t * t;
}

std::optional<LightLiSample> SpotLight::sampleLi(const Vec3& p, Point2) const {
    const Vec3 toLight = position - p;
    const double d = length(toLight);
    if (!(d > 0)) return std::nullopt;
    const Vec3 wi = toLight / d;
    const double f = falloff(-wi);
    if (!(f > 0)) return std::nullopt;
    const double att = attenuation.x + attenuation.y * d + attenuation.z * d * d;
    const double w = rangeWindow(d, range);
    if (!(w > 0)) return std::nullopt;
    return LightLiSample{wi, finiteRadiance(intensity * (f * w / att)), 1, 1, d, true};
}

double SpotLight::pdfLi(const Vec3&, const LightPoint&, double) const { return 0; }

std::optional<LightLeSample> SpotLight::sampleLe(Point2, Point2 uDir,
                                                 const LightLeContext& ctx) const {
    const auto [dir, pdf] = sampleTowardsSphere(position, ctx.center, ctx.radius, uDir);
    const double f = falloff(dir);
    if (!(f > 0)) return std::nullopt;
    const Vec3 L = intensity * f;
    return LightLeSample{
        Ray{position, dir, 0, kInfinity}, position, Vec3(0), L, L / pdf, 1, pdf, attenuation};
}

LightLePdf SpotLight::pdfLe(const Vec3&, const Vec3&, const Vec3& dir,
                            const LightLeContext& ctx) const {
    return {0, pdfTowardsSphere(position, ctx.center, ctx.radius, dir)};
}

std::optional<LightBounds> SpotLight::bounds() const {
    // As a point light's, in the same units (pbrt-v4's SpotLight::Bounds does the same), but
    // emitting within the outer cone about the axis only.
    const double att = std::max(attenuation.x + attenuation.y + attenuation.z, 1e-6);
    const double power = 4 * kPi * brightness(intensity) / att;
    if (!(power > 0)) return std::nullopt;
    LightBounds b = LightBounds::point(position, power);
    b.w = axis;
    b.cosThetaO = 1;
    b.cosThetaE = cosOuter;
    return b;
}

std::ostream& operator<<(std::ostream& out, const SpotLight& l) {
    out << "SpotLight{at " << l.position << ", axis " << l.axis << ", intensity " << l.intensity
        << ", attenuation " << l.attenuation << ", cos inner " << l.cosInner << ", cos outer "
        << l.cosOuter;
    if (l.range > 0) out << ", range " << l.range;
    return out << "}";
}

}  // namespace glint
