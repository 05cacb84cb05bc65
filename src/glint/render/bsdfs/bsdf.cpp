#include "glint/render/bsdfs/bsdf.h"

#include <algorithm>
#include <numbers>

#include "glint/render/bsdfs/bsdf_util.h"
#include "glint/render/bsdfs/ggx_albedo.h"
#include "glint/render/bsdfs/optics.h"

namespace glint {
namespace {

using enum BsdfFlags;
using namespace bsdf_util;

}  // namespace

// ---- Lambertian ----

Vec3 Lambertian::eval(const Vec3& wo, const Vec3& wi) const {
    return sameHemisphere(wo, wi) ? albedo * std::numbers::inv_pi : Vec3(0);
}

double Lambertian::pdf(const Vec3& wo, const Vec3& wi) const {
    return sameHemisphere(wo, wi) ? std::abs(wi.z) * std::numbers::inv_pi : 0;
}

std::optional<BsdfSample> Lambertian::sample(const Vec3& wo, double, Point2 u) const {
    if (wo.z == 0) return std::nullopt;
    Vec3 wi = sampleCosineHemisphere(u);
    if (wo.z < 0) wi = flipZ(wi);
    double pdf = std::abs(wi.z) * std::numbers::inv_pi;
    if (!(pdf > 0)) return std::nullopt;
    return BsdfSample{wi, albedo * std::numbers::inv_pi, pdf, Reflection | Diffuse};
}

// ---- Conductor ----

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

Vec3 Conductor::eval(const Vec3& wo, const Vec3& wi) const { return conductor(*this, wo, wi).f; }

double Conductor::pdf(const Vec3& wo, const Vec3& wi) const { return conductor(*this, wo, wi).pdf; }

std::optional<BsdfSample> Conductor::sample(const Vec3& wo, double uc, Point2 u) const {
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

// ---- Dielectric ----

namespace {

/// The rough dielectric's value and density at one pair of directions.
struct RoughDielectricLobe {
    double f = 0;    ///< The BSDF without the tint, 1 / sr.
    double pdf = 0;  ///< The density of Dielectric::sample(), 1 / sr.
};

/// The rough dielectric for a viewer above the surface (o.z > 0), where `eta` is the index
/// below over the index above: wo and wi mirrored in the surface plane when the viewer is
/// inside. Zero where no visible microfacet takes o to i.
RoughDielectricLobe roughDielectric(const Ggx& ggx, double eta, const Vec3& o, const Vec3& i) {
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
    // (n_o / n_i)^2 = 1 / eta^2 through the boundary.
    return {d * g2 * t * oh * jacobian / (o.z * -i.z * eta * eta), visible * jacobian * t};
}

}  // namespace

Vec3 Dielectric::eval(const Vec3& wo, const Vec3& wi) const {
    if (!rough()) return Vec3(0);
    bool outside = wo.z > 0;
    Vec3 o = outside ? wo : flipZ(wo), i = outside ? wi : flipZ(wi);
    return tint * roughDielectric(Ggx{alpha}, outside ? eta : 1 / eta, o, i).f;
}

double Dielectric::pdf(const Vec3& wo, const Vec3& wi) const {
    if (!rough()) return 0;
    bool outside = wo.z > 0;
    Vec3 o = outside ? wo : flipZ(wo), i = outside ? wi : flipZ(wi);
    return roughDielectric(Ggx{alpha}, outside ? eta : 1 / eta, o, i).pdf;
}

std::optional<BsdfSample> Dielectric::sample(const Vec3& wo, double uc, Point2 u) const {
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
        RoughDielectricLobe lobe = roughDielectric(ggx, etaBelow, o, i);
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
    // Radiance is scaled by (n_o / n_i)^2 = etaRel^2 through the boundary.
    return BsdfSample{wi, tint * (t * etaRel * etaRel / std::abs(wi.z)), t,
                      Transmission | Specular};
}

// ---- DiffuseSpecular ----

double DiffuseSpecular::specularProbability() const {
    double s = specular.x + specular.y + specular.z;
    double d = diffuse.x + diffuse.y + diffuse.z;
    return s > 0 ? s / (s + d) : 0;
}

Vec3 DiffuseSpecular::eval(const Vec3& wo, const Vec3& wi) const {
    Vec3 f = Lambertian{diffuse}.eval(wo, wi);
    if (alpha > 0) f += specular * Conductor{Vec3(1), alpha}.eval(wo, wi);
    return f;
}

double DiffuseSpecular::pdf(const Vec3& wo, const Vec3& wi) const {
    double ps = specularProbability();
    double pdf = (1 - ps) * Lambertian{diffuse}.pdf(wo, wi);
    if (alpha > 0) pdf += ps * Conductor{Vec3(1), alpha}.pdf(wo, wi);
    return pdf;
}

std::optional<BsdfSample> DiffuseSpecular::sample(const Vec3& wo, double uc, Point2 u) const {
    double ps = specularProbability();
    // uc < ps chooses the specular lobe; uc / ps is then uniform again, for its own choice.
    std::optional<BsdfSample> s = uc < ps ? Conductor{Vec3(1), alpha}.sample(wo, uc / ps, u)
                                          : Lambertian{diffuse}.sample(wo, uc, u);
    if (!s) return std::nullopt;
    if (s->isSpecular()) {  // the mirror: a delta, chosen with probability ps
        s->f = s->f * specular;
        s->pdf *= ps;
        return s;
    }
    // Either lobe could have drawn wi: the mixture's value and density (one-sample MIS).
    s->f = eval(wo, s->wi);
    s->pdf = pdf(wo, s->wi);
    return s;
}

Bsdf bsdfFromMaterial(const Material& m) {
    auto unit = [](const Vec3& c) { return min(max(c, Vec3(0)), Vec3(1)); };
    if (m.transmissive()) return {Dielectric{m.ior, unit(m.transmission), m.roughness}};
    Vec3 d = unit(m.diffuse), s = unit(m.specular);
    if (s == Vec3(0)) return {Lambertian{d}};
    for (int c = 0; c < 3; ++c) {
        double sum = d[c] + s[c];
        if (sum > 1) {
            d[c] /= sum;
            s[c] /= sum;
        }
    }
    return {DiffuseSpecular{d, s, m.roughness}};
}

}  // namespace glint
