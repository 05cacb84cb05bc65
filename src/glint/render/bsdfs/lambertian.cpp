#include "glint/render/bsdfs/lambertian.h"

#include <numbers>
#include <ostream>

#include "glint/render/bsdfs/bsdf_util.h"

namespace glint {

using namespace bsdf_util;

Vec3 Lambertian::eval(const Vec3& wo, const Vec3& wi, TransportMode) const {
    return sameHemisphere(wo, wi) ? albedo * std::numbers::inv_pi : Vec3(0);
}

double Lambertian::pdf(const Vec3& wo, const Vec3& wi, TransportMode) const {
    return sameHemisphere(wo, wi) ? std::abs(wi.z) * std::numbers::inv_pi : 0;
}

std::optional<BsdfSample> Lambertian::sample(const Vec3& wo, double, Point2 u,
                                             TransportMode) const {
    if (wo.z == 0) return std::nullopt;
    Vec3 wi = sampleCosineHemisphere(u);
    if (wo.z < 0) wi = flipZ(wi);
    double pdf = std::abs(wi.z) * std::numbers::inv_pi;
    if (!(pdf > 0)) return std::nullopt;
    return BsdfSample{wi, albedo * std::numbers::inv_pi, pdf,
                      BsdfFlags::Reflection | BsdfFlags::Diffuse};
}

std::ostream& operator<<(std::ostream& out, const Lambertian& l) {
    out << "Lambertian{albedo " << l.albedo << "}";
    return out;
}

}  // namespace glint
