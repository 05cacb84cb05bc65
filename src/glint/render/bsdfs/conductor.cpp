#include "glint/render/bsdfs/conductor.h"

#include <algorithm>
#include <numbers>
#include <ostream>

#include "glint/render/bsdfs/bsdf_util.h"
#include "glint/render/bsdfs/ggx_albedo.h"
#include "glint/render/bsdfs/optics.h"

namespace glint {

using enum BsdfFlags;
using namespace bsdf_util;

namespace {

/// Kulla and Conty's compensation of the GGX conductor for one roughness, Fresnel colour and
/// viewer: the multiple-scattering lobe f_ms = scale (1 - E(cos_i)), and the probability with
/// which sample() draws from its cosine-weighted density instead of the visible normals.
struct Compensation {
    GgxAlbedo albedo;
    Vec3 scale{0};
    double cosineProbability = 0;
};

/// Kulla and Conty's lobe for a viewer at cos_o = `cosO` > 0 (see Conductor in bsdf.h).
Compensation compensation(const Vec3& f0, double alpha, double cosO) {
    Compensation c{GgxAlbedo(alpha)};
    double eo = c.albedo(cosO), eavg = c.albedo.average();
    if (!(eavg < 1) || !(eo < 1)) return c;  // nothing lost: nothing to give back
    Vec3 favg = f0 + (Vec3(1) - f0) * (1.0 / 21);
    Vec3 fms = favg * favg * eavg / (Vec3(1) - favg * (1 - eavg));
    c.scale = fms * ((1 - eo) / (std::numbers::pi * (1 - eavg)));
    // The two lobes' albedos at wo, with F_avg standing for the single-scattering Fresnel.
    double single = eo * (favg.x + favg.y + favg.z), multiple = (1 - eo) * (fms.x + fms.y + fms.z);
    c.cosineProbability = multiple / (single + multiple);
    return c;
}

/// The conductor's value and density for o, i above the surface.
struct ConductorLobe {
    Vec3 f{0};
    double pdf = 0;
};

/// The rough conductor `c` at o, i above the surface; `comp` is compensation(c, o.z), or null
/// for the single-scattering lobe alone.
ConductorLobe conductor(const Conductor& c, const Compensation* comp, const Vec3& o,
                        const Vec3& i) {
    Ggx ggx{c.alpha};
    Vec3 h = normalize(o + i);
    ConductorLobe lobe{ggxReflection(ggx, c.f0, o, i, h), ggxReflectionPdf(ggx, o, h)};
    if (comp) {
        lobe.f += comp->scale * std::max(0.0, 1 - comp->albedo(i.z));
        double p = comp->cosineProbability;
        lobe.pdf = (1 - p) * lobe.pdf + p * i.z * std::numbers::inv_pi;
    }
    return lobe;
}

/// The conductor `c` at wo, wi, two-sided: mirrored in the surface when wo is below it.
ConductorLobe conductor(const Conductor& c, const Vec3& wo, const Vec3& wi) {
    if (c.alpha == 0 || !sameHemisphere(wo, wi)) return {};
    Vec3 o = wo.z > 0 ? wo : flipZ(wo), i = wo.z > 0 ? wi : flipZ(wi);
    if (!c.multipleScattering) return conductor(c, nullptr, o, i);
    Compensation comp = compensation(c.f0, c.alpha, o.z);
    return conductor(c, &comp, o, i);
}

}  // namespace

Vec3 Conductor::eval(const Vec3& wo, const Vec3& wi, TransportMode) const {
    return conductor(*this, wo, wi).f;
}

double Conductor::pdf(const Vec3& wo, const Vec3& wi, TransportMode) const {
    return conductor(*this, wo, wi).pdf;
}

std::optional<BsdfSample> Conductor::sample(const Vec3& wo, double uc, Point2 u,
                                            TransportMode) const {
    if (wo.z == 0) return std::nullopt;
    Vec3 o = wo.z > 0 ? wo : flipZ(wo);
    if (alpha == 0) return BsdfSample{mirror(wo), schlick(f0, o.z) / o.z, 1, Reflection | Specular};
    Ggx ggx{alpha};
    if (!multipleScattering) {
        Vec3 h = ggx.sampleVisibleNormal(o, u.x, u.y);
        Vec3 i = normalize(h * (2 * dot(o, h)) - o);
        if (!(i.z > 0)) return std::nullopt;  // reflected below the surface: shadowed
        double pdf = ggxReflectionPdf(ggx, o, h);
        if (!(pdf > 0)) return std::nullopt;
        return BsdfSample{wo.z > 0 ? i : flipZ(i), ggxReflection(ggx, f0, o, i, h), pdf,
                          Reflection | Glossy};
    }
    // One sample of either strategy, cosine-weighted or visible normals, chosen in proportion
    // to the albedos of the lobes they suit; f and pdf are those of the whole BSDF (one-sample
    // MIS, as in DiffuseSpecular).
    Compensation comp = compensation(f0, alpha, o.z);
    Vec3 i;
    if (uc < comp.cosineProbability) {
        i = sampleCosineHemisphere(u);
    } else {
        Vec3 h = ggx.sampleVisibleNormal(o, u.x, u.y);
        i = normalize(h * (2 * dot(o, h)) - o);
    }
    if (!(i.z > 0)) return std::nullopt;  // shadowed, or the rim of the cosine density
    ConductorLobe lobe = conductor(*this, &comp, o, i);
    if (!(lobe.pdf > 0)) return std::nullopt;
    return BsdfSample{wo.z > 0 ? i : flipZ(i), lobe.f, lobe.pdf, Reflection | Glossy};
}

std::ostream& operator<<(std::ostream& out, const Conductor& c) {
    out << "Conductor{f0 " << c.f0 << ", alpha " << c.alpha
        << (c.multipleScattering ? "" : ", single scattering") << "}";
    return out;
}

}  // namespace glint
