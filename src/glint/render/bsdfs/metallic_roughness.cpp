// glTF's metallic-roughness BSDF and its layers (metallic_roughness.h): the base of
// the specification's appendix B with the specular, anisotropy, iridescence, transmission,
// diffuse transmission and volume extensions, under the sheen and clearcoat layers.

#include "glint/render/bsdfs/metallic_roughness.h"

#include <algorithm>
#include <numbers>
#include <ostream>

#include "glint/render/bsdfs/bsdf_util.h"
#include "glint/render/bsdfs/dielectric.h"
#include "glint/render/bsdfs/optics.h"
#include "glint/render/bsdfs/sheen.h"
#include "glint/render/bsdfs/thin_film.h"

namespace glint {
namespace {

using enum BsdfFlags;
using namespace bsdf_util;

constexpr double kInvPi = std::numbers::inv_pi;
/// The clearcoat's normal-incidence reflectance: an index of 1.5, as the extension fixes it.
constexpr double kCoatF0 = 0.04;

}  // namespace

// ---- The base ----

Vec3 MetallicRoughness::dielectricFresnel(double c) const {
    const double r = (eta - 1) / (eta + 1);
    const Vec3 f0 = min(specularColor * (r * r), Vec3(1)) * specular;
    Vec3 f = f0 + (Vec3(specular) - f0) * schlickWeight(c);
    if (iridescence.weight > 0)
        f += (thinFilmReflectance(c, iridescence.ior, iridescence.thickness, f0) - f) *
             iridescence.weight;
    return f;
}

Vec3 MetallicRoughness::metalFresnel(double c) const {
    Vec3 f = schlick(baseColor, c);
    if (iridescence.weight > 0)
        f += (thinFilmReflectance(c, iridescence.ior, iridescence.thickness, baseColor) - f) *
             iridescence.weight;
    return f;
}

namespace {

/// The GGX of the reflection lobes: anisotropic along x when asked.
Ggx reflectionGgx(const MetallicRoughness& m) {
    if (!(m.anisotropy > 0)) return Ggx{m.alpha};
    const double a = std::min(m.anisotropy, 1.0);
    return Ggx{m.alpha + (1 - m.alpha) * a * a, m.alpha};
}

/// The refracting volume's boundary (KHR_materials_volume).
Dielectric volumeOf(const MetallicRoughness& m) { return {m.eta, m.baseColor, m.alpha}; }

}  // namespace

MetallicRoughness::Weights MetallicRoughness::weights(const Vec3& o) const {
    const Vec3 fd = dielectricFresnel(o.z);
    const double fm = mean(metalFresnel(o.z));
    const double kd = (1 - metallic) * (1 - transmission), kt = (1 - metallic) * transmission;
    const Vec3 passed = Vec3(1) - fd;
    Weights w;
    w.spec = kd * mean(fd) + metallic * fm + (thin ? kt * mean(fd) : 0);
    w.diffuse = kd * (1 - diffuseTransmission) * mean(passed * baseColor);
    w.diffuseTrans = kd * diffuseTransmission * mean(passed * diffuseTransmissionColor);
    w.trans = thin ? kt * mean(passed * baseColor) : kt;
    return w;
}

Vec3 MetallicRoughness::baseEval(const Vec3& wo, const Vec3& wi, TransportMode mode) const {
    const double kt = (1 - metallic) * transmission;
    const double kd = (1 - metallic) * (1 - transmission);
    Vec3 f(0);
    if (!thin && kt > 0) f += volumeOf(*this).eval(wo, wi, mode) * kt;
    Vec3 o = wo.z > 0 ? wo : flipZ(wo), i = wo.z > 0 ? wi : flipZ(wi);
    if (!sameHemisphere(wo, wi)) {
        if (diffuseTransmission > 0 && o.z > 0 && i.z < 0)
            f += (Vec3(1) - dielectricFresnel(o.z)) * diffuseTransmissionColor *
                 (kd * diffuseTransmission * kInvPi);
        return f;
    }
    const Vec3 h = normalize(o + i);
    const double oh = std::abs(dot(o, h));
    const Vec3 fd = dielectricFresnel(oh);
    const Ggx ggx = reflectionGgx(*this);
    const double s = ggx.d(h) * ggx.g2(o, i) / (4 * o.z * i.z);
    const Vec3 specWeight = fd * (kd + (thin ? kt : 0));
    f += (Vec3(1) - fd) * baseColor * (kd * (1 - diffuseTransmission) * kInvPi) +
         (specWeight + metalFresnel(oh) * metallic) * s;
    return f;
}

double MetallicRoughness::basePdf(const Vec3& wo, const Vec3& wi) const {
    if (wo.z == 0) return 0;
    Vec3 o = wo.z > 0 ? wo : flipZ(wo);
    const Weights w = weights(o);
    const double sum = w.sum();
    if (!(sum > 0)) return 0;
    double pdf = 0;
    if (!thin && w.trans > 0) pdf += w.trans * volumeOf(*this).pdf(wo, wi);
    Vec3 i = wo.z > 0 ? wi : flipZ(wi);
    if (!sameHemisphere(wo, wi)) {
        if (i.z < 0) pdf += w.diffuseTrans * -i.z * kInvPi;
        return pdf / sum;
    }
    pdf += w.spec * ggxReflectionPdf(reflectionGgx(*this), o, normalize(o + i));
    pdf += w.diffuse * i.z * kInvPi;
    return pdf / sum;
}

std::optional<BsdfSample> MetallicRoughness::baseSample(const Vec3& wo, double uc, Point2 u,
                                                        TransportMode mode) const {
    if (wo.z == 0) return std::nullopt;
    Vec3 o = wo.z > 0 ? wo : flipZ(wo);
    const Weights w = weights(o);
    const double sum = w.sum();
    if (!(sum > 0)) return std::nullopt;
    uc *= sum;  // choices against the unnormalised weights
    Vec3 i;
    if (uc < w.spec) {
        Vec3 h = reflectionGgx(*this).sampleVisibleNormal(o, u.x, u.y);
        i = normalize(h * (2 * dot(o, h)) - o);
        if (!(i.z > 0)) return std::nullopt;  // reflected below the surface: shadowed
    } else if (uc < w.spec + w.diffuse) {
        i = sampleCosineHemisphere(u);
    } else if (uc < w.spec + w.diffuse + w.diffuseTrans) {
        i = flipZ(sampleCosineHemisphere(u));
    } else if (w.trans > 0) {
        const double kt = (1 - metallic) * transmission;
        if (thin) {  // straight through: a delta
            const Vec3 passed = Vec3(1) - dielectricFresnel(o.z);
            return BsdfSample{-wo, passed * baseColor * (kt / o.z), w.trans / sum,
                              Transmission | Specular};
        }
        const double ut =
            std::min((uc - w.spec - w.diffuse - w.diffuseTrans) / w.trans, 0.999999999);
        std::optional<BsdfSample> ds = volumeOf(*this).sample(wo, ut, u, mode);
        if (!ds) return std::nullopt;
        if (ds->isSpecular()) {
            ds->f = ds->f * kt;
            ds->pdf *= w.trans / sum;
            return ds;
        }
        i = wo.z > 0 ? ds->wi : flipZ(ds->wi);
    } else {
        return std::nullopt;
    }
    const Vec3 wi = wo.z > 0 ? i : flipZ(i);
    const double p = basePdf(wo, wi);
    if (!(p > 0)) return std::nullopt;
    return BsdfSample{wi, baseEval(wo, wi, mode), p,
                      (sameHemisphere(wo, wi) ? Reflection : Transmission) | Glossy};
}

BsdfFlags MetallicRoughness::flags() const {
    BsdfFlags f = Reflection | Glossy;
    if ((1 - metallic) * (1 - transmission) > 0) f = f | Diffuse;
    if (transmission > 0 || diffuseTransmission > 0) f = f | Transmission;
    if (transmission > 0 && metallic < 1 && (thin || !volumeOf(*this).rough())) f = f | Specular;
    return f;
}

double MetallicRoughness::etaOfChannel(int c) const {
    if (!(dispersion > 0)) return eta;
    constexpr double kWavelength[3] = {610, 550, 465};  // nanometres
    const double abbe = 20 / dispersion;
    const double l = kWavelength[std::clamp(c, 0, 2)];
    return std::max(1.0, eta + (eta - 1) / abbe * (523655 / (l * l) - 1.5168));
}

// ---- The layers: sheen, then the clearcoat over everything ----

namespace {

/// The coat's normal for a viewer at o: mirrored with the view when the viewer is below.
Vec3 coatNormal(const CoatLayer& c, bool below) {
    return below ? Vec3(-c.normal.x, -c.normal.y, c.normal.z) : c.normal;
}

/// The coat's lobe and density (without its weight) for o above the surface and i, with n
/// its normal: a GGX lobe about n, divided by cos_i rather than n.i (CoatLayer).
struct CoatLobe {
    double f = 0, pdf = 0;
};
CoatLobe coatLobe(const CoatLayer& c, const Vec3& n, const Vec3& o, const Vec3& i) {
    if (!(i.z > 0)) return {};
    const Frame frame(n);
    const Vec3 oc = frame.toLocal(o), ic = frame.toLocal(i);
    if (!(oc.z > 0) || !(ic.z > 0)) return {};
    const Ggx ggx{c.alpha};
    const Vec3 h = normalize(oc + ic);
    return {ggx.d(h) * ggx.g2(oc, ic) / (4 * oc.z * i.z), ggxReflectionPdf(ggx, oc, h)};
}

/// The share of the base that the sheen leaves (the specification's albedo scaling).
double sheenScaling(const SheenLayer& s, double cosO, double cosI) {
    const double m = maxComponent(s.color);
    if (!(m > 0)) return 1;
    const double e = std::max(sheenAlbedo(s.alpha, cosO), sheenAlbedo(s.alpha, cosI));
    return std::max(0.0, 1 - m * e);
}

}  // namespace

MetallicRoughness::LayerChoice MetallicRoughness::layerChoice(const Vec3& o, bool below) const {
    LayerChoice c;
    if (coat.weight > 0)
        c.coatFresnel =
            coat.weight * schlick(Vec3(kCoatF0), std::abs(dot(coatNormal(coat, below), o))).x;
    const double under = 1 - c.coatFresnel;
    double sheenShare = 0, baseShare = 1;
    if (!(sheen.color == Vec3(0))) {
        const double e = sheenAlbedo(sheen.alpha, o.z);
        sheenShare = mean(sheen.color) * e;
        baseShare = 1 - maxComponent(sheen.color) * e;
    }
    const double a = c.coatFresnel, s = under * sheenShare,
                 b = under * std::max(0.0, baseShare) * weights(o).sum();
    const double sum = a + s + b;
    if (!(sum > 0)) return {};
    c.coat = a / sum;
    c.sheen = s / sum;
    c.base = b / sum;
    return c;
}

Vec3 MetallicRoughness::eval(const Vec3& wo, const Vec3& wi, TransportMode mode) const {
    Vec3 f = baseEval(wo, wi, mode);
    if (!layered() || wo.z == 0) return f;
    const bool below = wo.z < 0;
    const Vec3 o = below ? flipZ(wo) : wo, i = below ? flipZ(wi) : wi;
    if (!(sheen.color == Vec3(0))) {
        f = f * sheenScaling(sheen, o.z, std::abs(i.z));
        if (i.z > 0) f += sheen.color * sheenLobe(sheen.alpha, o, i);
    }
    if (coat.weight > 0) {
        const Vec3 n = coatNormal(coat, below);
        const double fc = coat.weight * schlick(Vec3(kCoatF0), std::abs(dot(n, o))).x;
        f = f * (1 - fc) + Vec3(fc * coatLobe(coat, n, o, i).f);
    }
    return f;
}

double MetallicRoughness::pdf(const Vec3& wo, const Vec3& wi, TransportMode) const {
    if (!layered()) return basePdf(wo, wi);
    if (wo.z == 0) return 0;
    const bool below = wo.z < 0;
    const Vec3 o = below ? flipZ(wo) : wo, i = below ? flipZ(wi) : wi;
    const LayerChoice c = layerChoice(o, below);
    double pdf = c.base > 0 ? c.base * basePdf(wo, wi) : 0;
    if (c.sheen > 0 && i.z > 0) pdf += c.sheen * i.z * kInvPi;
    if (c.coat > 0) pdf += c.coat * coatLobe(coat, coatNormal(coat, below), o, i).pdf;
    return pdf;
}

std::optional<BsdfSample> MetallicRoughness::sample(const Vec3& wo, double uc, Point2 u,
                                                    TransportMode mode) const {
    if (!layered()) return baseSample(wo, uc, u, mode);
    if (wo.z == 0) return std::nullopt;
    const bool below = wo.z < 0;
    const Vec3 o = below ? flipZ(wo) : wo;
    const LayerChoice c = layerChoice(o, below);
    Vec3 i;
    if (uc < c.coat) {
        const Frame frame(coatNormal(coat, below));
        const Vec3 oc = frame.toLocal(o);
        if (!(oc.z > 0)) return std::nullopt;
        const Vec3 h = Ggx{coat.alpha}.sampleVisibleNormal(oc, u.x, u.y);
        const Vec3 ic = normalize(h * (2 * dot(oc, h)) - oc);
        if (!(ic.z > 0)) return std::nullopt;
        i = frame.toWorld(ic);
        if (!(i.z > 0)) return std::nullopt;
    } else if (uc < c.coat + c.sheen) {
        i = sampleCosineHemisphere(u);
    } else if (c.base > 0) {
        const double ub = std::min((uc - c.coat - c.sheen) / c.base, 0.999999999);
        std::optional<BsdfSample> bs = baseSample(wo, ub, u, mode);
        if (!bs) return std::nullopt;
        if (bs->isSpecular()) {  // a delta of the base, seen through the layers
            const double fromBelow = std::abs(bs->wi.z);
            bs->f = bs->f * (sheenScaling(sheen, o.z, fromBelow) * (1 - c.coatFresnel));
            bs->pdf *= c.base;
            return bs;
        }
        i = below ? flipZ(bs->wi) : bs->wi;
    } else {
        return std::nullopt;
    }
    const Vec3 wi = below ? flipZ(i) : i;
    const double p = pdf(wo, wi);
    if (!(p > 0)) return std::nullopt;
    return BsdfSample{wi, eval(wo, wi, mode), p,
                      (sameHemisphere(wo, wi) ? Reflection : Transmission) | Glossy};
}

std::ostream& operator<<(std::ostream& out, const MetallicRoughness& m) {
    out << "MetallicRoughness{baseColor " << m.baseColor << ", metallic " << m.metallic
        << ", alpha " << m.alpha << ", transmission " << m.transmission << ", eta " << m.eta
        << (m.thin ? ", thin" : "");
    if (m.diffuseTransmission > 0) out << ", diffuseTransmission " << m.diffuseTransmission;
    if (m.anisotropy > 0) out << ", anisotropy " << m.anisotropy;
    if (m.dispersion > 0) out << ", dispersion " << m.dispersion;
    if (m.iridescence.weight > 0) out << ", iridescence " << m.iridescence.weight;
    if (!(m.sheen.color == Vec3(0))) out << ", sheen " << m.sheen.color;
    if (m.coat.weight > 0) out << ", coat " << m.coat.weight;
    out << "}";
    return out;
}

}  // namespace glint
