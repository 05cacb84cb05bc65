#include "glint/render/bsdfs/dielectric.h"

#include <ostream>

#include "glint/render/bsdfs/bsdf_util.h"
#include "glint/render/bsdfs/optics.h"

namespace glint {

using enum BsdfFlags;
using namespace bsdf_util;

namespace {

/// The rough dielectric's value and density at one pair of directions.
struct RoughDielectricLobe {
    double f = 0;    ///< The BSDF without the tint, 1 / sr.
    double pdf = 0;  ///< The density of Dielectric::sample(), 1 / sr.
};

/// The rough dielectric for a viewer above the surface (o.z > 0), where `eta` is the index
/// below over the index above: wo and wi mirrored in the surface plane when the viewer is
/// inside. Zero where no visible microfacet takes o to i.
RoughDielectricLobe roughDielectric(const Ggx& ggx, double eta, const Vec3& o, const Vec3& i,
                                    TransportMode mode) {
    if (!(o.z > 0) || i.z == 0) return {};
    bool transmission = i.z < 0;
    double etaI = transmission ? eta : 1;  // the index on i's side over o's
    // Walter's generalized half-vector (eq. 16), the microfacet normal, turned to +z.
    Vec3 h = o + i * etaI;
    double len2 = dot(h, h);
    if (!(len2 > 0)) return {};
    h = h / std::sqrt(len2);
    if (h.z < 0) h = -h;
    double oh = dot(o, h), ih = dot(i, h);
    // Both directions must see the microfacet's front (Walter's chi+ in G1).
    if (!(oh > 0) || !(ih * i.z > 0)) return {};
    double r = fresnelDielectric(oh, 1 / eta);  // 1 under total internal reflection at h
    double d = ggx.d(h);
    double g2 = ggx.g1(o) * ggx.g1(Vec3(i.x, i.y, std::abs(i.z)));
    double visible = ggx.g1(o) * oh * d / o.z;  // D_o(h), Heitz 2018, eq. 3
    if (!transmission) return {d * g2 * r / (4 * o.z * i.z), visible / (4 * oh) * r};
    double s = ih + oh / eta;
    double jacobian = -ih / (s * s);  // |dh / di| (Walter eq. 17), i.h < 0
    double t = 1 - r;
    // D G2 (1 - F) |i.h| |o.h| / (|cos_o cos_i| (i.h + o.h / eta)^2), and radiance is scaled by
    // (n_o / n_i)^2 = 1 / eta^2 through the boundary (importance is not).
    const double cosines = mode == TransportMode::Radiance ? o.z * -i.z * eta * eta : o.z * -i.z;
    return {d * g2 * t * oh * jacobian / cosines, visible * jacobian * t};
}

}  // namespace

Vec3 Dielectric::eval(const Vec3& wo, const Vec3& wi, TransportMode mode) const {
    if (!rough()) return Vec3(0);
    bool outside = wo.z > 0;
    Vec3 o = outside ? wo : flipZ(wo), i = outside ? wi : flipZ(wi);
    return tint * roughDielectric(Ggx{alpha}, outside ? eta : 1 / eta, o, i, mode).f;
}

double Dielectric::pdf(const Vec3& wo, const Vec3& wi, TransportMode mode) const {
    if (!rough()) return 0;
    bool outside = wo.z > 0;
    Vec3 o = outside ? wo : flipZ(wo), i = outside ? wi : flipZ(wi);
    return roughDielectric(Ggx{alpha}, outside ? eta : 1 / eta, o, i, mode).pdf;
}

std::optional<BsdfSample> Dielectric::sample(const Vec3& wo, double uc, Point2 u,
                                             TransportMode mode) const {
    if (wo.z == 0) return std::nullopt;
    bool outside = wo.z > 0;
    if (rough()) {
        // Mirrored in the surface when inside: o above, and the indices swap.
        Vec3 o = outside ? wo : flipZ(wo);
        double etaBelow = outside ? eta : 1 / eta;  // below over above, in o's frame
        Ggx ggx{alpha};
        Vec3 h = ggx.sampleVisibleNormal(o, u.x, u.y);
        double oh = dot(o, h);
        bool reflect = uc < fresnelDielectric(oh, 1 / etaBelow);
        Vec3 i;
        if (reflect) {
            i = normalize(h * (2 * oh) - o);
            if (!(i.z > 0)) return std::nullopt;  // reflected below the surface: shadowed
        } else {
            if (!refract(-o, h, 1 / etaBelow, i)) return std::nullopt;  // F = 1: not reached
            if (!(i.z < 0)) return std::nullopt;  // refracted back above: shadowed
        }
        RoughDielectricLobe lobe = roughDielectric(ggx, etaBelow, o, i, mode);
        if (!(lobe.pdf > 0)) return std::nullopt;
        return BsdfSample{outside ? i : flipZ(i), tint * lobe.f, lobe.pdf,
                          reflect ? Reflection | Glossy : Transmission | Glossy};
    }
    double etaRel = outside ? 1 / eta : eta;  // index on wo's side over the other side's
    double cosO = std::abs(wo.z);
    double r = fresnelDielectric(cosO, etaRel);  // 1 under total internal reflection
    if (uc < r) return BsdfSample{mirror(wo), tint * (r / cosO), r, Reflection | Specular};
    Vec3 wi;
    if (!refract(-wo, Vec3(0, 0, outside ? 1 : -1), etaRel, wi)) return std::nullopt;
    double t = 1 - r;
    // Radiance is scaled by (n_o / n_i)^2 = etaRel^2 through the boundary (importance is not).
    const double scaled = mode == TransportMode::Radiance ? t * etaRel * etaRel : t;
    return BsdfSample{wi, tint * (scaled / std::abs(wi.z)), t, Transmission | Specular};
}

std::ostream& operator<<(std::ostream& out, const Dielectric& d) {
    out << "Dielectric{eta " << d.eta << ", tint " << d.tint << ", alpha " << d.alpha << "}";
    return out;
}

}  // namespace glint
