#pragma once
/// A metal: Schlick's Fresnel over a perfect mirror or the compensated GGX microfacet lobe
/// (bsdf.h's conventions).

#include <iosfwd>
#include <optional>

#include "glint/math/sampling.h"
#include "glint/render/bsdfs/bsdf_sample.h"

namespace glint {

/// A metal: Schlick's approximation of the Fresnel reflectance, F = f0 + (1 - f0)(1 - cos)^5
/// (Schlick, "An Inexpensive BRDF Model for Physically-based Rendering", 1994) with cos the
/// angle between wo and the micro-normal. alpha = 0 is a perfect mirror (a delta lobe);
/// alpha > 0 the GGX (Trowbridge-Reitz) microfacet BRDF with separable Smith masking,
/// f_ss = D G2 F / (4 cos_o cos_i) (Walter et al., EGSR 2007), plus Kulla and Conty's energy
/// compensation for the light that bounces between microfacets more than once ("Revisiting
/// Physically Based Shading at Imageworks", SIGGRAPH 2017 course), which single scattering
/// loses (up to 69% at alpha = 1, from normal incidence):
///     f = f_ss + f_ms,  f_ms = F_ms (1 - E(cos_o)) (1 - E(cos_i)) / (pi (1 - E_avg)),
/// E(mu) the directional albedo of f_ss with F = 1 and E_avg its cosine-weighted average
/// (ggx_albedo.h: a table of this lobe's own E, not the height-correlated one). With F = 1,
/// f_ms reflects exactly what f_ss loses, so the directional albedo is 1 at every angle and
/// roughness, to the table's error (ggx_albedo_table::kMaxError: 6.2e-4 for alpha >= 1e-3; the
/// compensation fades out below). For a coloured
/// f0, F_ms = F_avg^2 E_avg / (1 - F_avg (1 - E_avg)), the light that leaves after two or more
/// bounces each reflecting F_avg, the cosine-weighted average of Schlick's F over the
/// hemisphere, f0 + (1 - f0) / 21; F_ms <= F_avg^2 <= 1, so no channel gains energy. f_ms is
/// symmetric in wo and wi (reciprocal) and smooth, like a Lambertian lobe that peaks where
/// the GGX lobe loses most.
///
/// sample() draws wi through the distribution of visible normals (optics.h; alone, its weight
/// is F G1(wi)) or, with probability p = A_ms / (A_ss + A_ms), cosine-weighted, where
/// A_ss = E(cos_o) mean(F_avg) and A_ms = (1 - E(cos_o)) mean(F_ms) estimate the two lobes'
/// albedos at wo; the returned f and pdf are the whole f and the mixture's density (one-sample
/// MIS), as eval() and pdf() give them. The cosine density matches f_ms poorly for smooth
/// surfaces: below alpha ~ 0.03, f_ms is small but concentrated at grazing wi, where 1 - E
/// reaches 0.12 while 1 - E_avg is 0.004 (alpha 0.03) to 2e-5 (alpha 1e-3), so the rare
/// cosine-weighted draws that land there weigh up to (1 - E) / (1 - E_avg), 30 to 7000: an
/// unbiased but noisy estimate near grazing views of nearly smooth metal (drawing wi in
/// proportion to (1 - E(cos_i)) cos_i, from a per-row table of its integral, would remove
/// this). With `multipleScattering` false the lobe is f_ss alone, sampled by visible normals
/// only (Cycles offers the same choice: "GGX" or "Multiscatter GGX").
struct Conductor {
    Vec3 f0;           ///< Reflectance at normal incidence, each channel in [0, 1].
    double alpha = 0;  ///< GGX roughness in [0, 1].
    /// Kulla and Conty's compensation (f_ms above); false: single scattering only.
    bool multipleScattering = true;

    Vec3 eval(const Vec3& wo, const Vec3& wi, TransportMode mode = TransportMode::Radiance) const;
    std::optional<BsdfSample> sample(const Vec3& wo, double uc, Point2 u,
                                     TransportMode mode = TransportMode::Radiance) const;
    double pdf(const Vec3& wo, const Vec3& wi, TransportMode mode = TransportMode::Radiance) const;

    BsdfFlags flags() const {
        return BsdfFlags::Reflection | (alpha == 0 ? BsdfFlags::Specular : BsdfFlags::Glossy);
    }
    std::optional<double> relativeEta() const { return std::nullopt; }
    bool disperses() const { return false; }
    void selectChannel(int) {}
    /// A perfect mirror shows what it reflects; a rough metal its colour.
    std::optional<Vec3> passAlbedo() const {
        return alpha == 0 ? std::nullopt : std::optional<Vec3>(f0);
    }
    bool castsCaustics() const { return alpha < kCausticAlpha; }
};

/// Its parameters, for messages and failing tests.
std::ostream& operator<<(std::ostream& out, const Conductor& c);

}  // namespace glint
