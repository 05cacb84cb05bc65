#pragma once
/// Bidirectional scattering distribution functions (BSDFs) for a physically based integrator,
/// in lajolla's style: a std::variant of small value structs, dispatched without allocation
/// or virtual calls. Everything is in a local shading frame whose normal is +z; wo and wi are
/// unit directions pointing away from the surface (wo towards the viewer, wi towards the
/// light), as in pbrt.
///
/// Conventions (pbrt-v4's):
///  - eval(wo, wi) is f, in 1 / sr; the integrand is f |cos theta_i| L_i.
///  - sample(wo, uc, u) draws wi with density pdf (1 / sr) and returns f there: f |cos| / pdf
///    is the estimator's weight. Delta lobes (perfect mirrors and refraction) have no density:
///    eval() and pdf() are 0 for them, and sample() returns f and pdf as the delta's
///    coefficients (the discrete probability of choosing that lobe), whose ratio is still the
///    weight.
///  - Transport: the functions are for radiance, traced from the camera (pbrt's
///    TransportMode::Radiance). Refraction into a medium of higher index compresses the
///    light's solid angle, so the transmitted f carries the factor (n_o / n_i)^2, n_o on wo's
///    side (1 / 2.25 for light leaving glass towards a viewer in air). Glint traces no paths
///    from the lights, so importance transport (which omits the factor) is not provided.
///  - Opaque lobes are two-sided: a wo below the surface sees the mirror image of the lobe.
///
/// The Whitted integrator does not use these: the course's Blinn-Phong term is not a BSDF.

#include <cmath>
#include <cstdint>
#include <optional>
#include <variant>

#include "glint/math/sampling.h"
#include "glint/math/vec3.h"
#include "glint/render/bsdfs/sheen.h"
#include "glint/scene/material.h"

namespace glint {

/// What kind of scattering a sampled direction comes from (pbrt's BxDFFlags): reflection or
/// transmission, and diffuse, glossy or specular (a delta).
enum class BsdfFlags : uint8_t {
    None = 0,
    Reflection = 1,
    Transmission = 2,
    Diffuse = 4,
    Glossy = 8,
    Specular = 16,
};
constexpr BsdfFlags operator|(BsdfFlags a, BsdfFlags b) {
    return static_cast<BsdfFlags>(static_cast<uint8_t>(a) | static_cast<uint8_t>(b));
}
/// Whether `flags` has any of the bits of `bits`.
constexpr bool hasAny(BsdfFlags flags, BsdfFlags bits) {
    return (static_cast<uint8_t>(flags) & static_cast<uint8_t>(bits)) != 0;
}

/// A direction drawn by a BSDF.
struct BsdfSample {
    Vec3 wi;  ///< Unit, local frame.
    Vec3 f;   ///< BSDF value (delta lobes: its coefficient), 1 / sr.
    /// Density of wi over solid angle, 1 / sr (delta lobes: the probability of the lobe).
    double pdf = 0;
    BsdfFlags flags = BsdfFlags::None;

    bool isSpecular() const { return hasAny(flags, BsdfFlags::Specular); }
    bool isTransmission() const { return hasAny(flags, BsdfFlags::Transmission); }
    /// The estimator's weight f |cos theta_i| / pdf.
    Vec3 weight() const { return f * (std::abs(wi.z) / pdf); }
};

/// Ideal diffuse reflection: f = albedo / pi, sampled with a cosine-weighted density.
struct Lambertian {
    Vec3 albedo;  ///< Directional albedo, each channel in [0, 1].

    Vec3 eval(const Vec3& wo, const Vec3& wi) const;
    std::optional<BsdfSample> sample(const Vec3& wo, double uc, Point2 u) const;
    double pdf(const Vec3& wo, const Vec3& wi) const;
};

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

    Vec3 eval(const Vec3& wo, const Vec3& wi) const;
    std::optional<BsdfSample> sample(const Vec3& wo, double uc, Point2 u) const;
    double pdf(const Vec3& wo, const Vec3& wi) const;
};

/// A boundary between the outside (+z, index 1) and a dielectric of index `eta`, reflecting and
/// transmitting by the exact Fresnel reflectance; `tint` scales both lobes, as the course's
/// `transmission` does. A wo below the surface is a viewer inside: the indices swap.
///  - alpha = 0 (or eta = 1, where nothing bends): smooth, specular reflection and refraction,
///    one chosen with the Fresnel reflectance R as its probability (uc < R reflects), so each
///    weight is `tint` (times the radiance factor of refraction, see above).
///  - alpha > 0: GGX microfacet reflection and transmission after Walter et al., "Microfacet
///    Models for Refraction through Rough Surfaces" (EGSR 2007), as pbrt-v4's DielectricBxDF
///    (there with height-correlated masking; here the separable Smith G1(wo) G1(wi) of the
///    Conductor). With n_o, n_i the indices on wo's and wi's sides and h the microfacet normal
///    (the generalized half-vector n_o wo + n_i wi, turned to +z), F the Fresnel reflectance
///    at wo.h:
///      reflection    f = D(h) G2 F / (4 |cos_o cos_i|)
///      transmission  f = D(h) G2 (1 - F) |wi.h wo.h| / (|cos_o cos_i| (wi.h + wo.h n_o/n_i)^2)
///                        * (n_o / n_i)^2
///    sample() draws h from the normals visible from wo (optics.h), then reflects with
///    probability F and refracts otherwise: the weight is tint G1(wi) times the radiance
///    factor for a transmission. Under total internal reflection at h, F = 1. Single
///    scattering: rays the microsurface would scatter again (reflected below it, refracted
///    back above it) are lost, more of them the rougher the surface.
/// Reciprocity with refraction holds for f / n_o^2: f(wo, wi) / n_o^2 = f(wi, wo) / n_i^2.
struct Dielectric {
    double eta = 1.5;  ///< Index of refraction inside (below the surface) over outside.
    Vec3 tint{1};      ///< Each channel in [0, 1].
    double alpha = 0;  ///< GGX roughness in [0, 1]; 0 is the smooth (delta) boundary.

    Vec3 eval(const Vec3& wo, const Vec3& wi) const;
    std::optional<BsdfSample> sample(const Vec3& wo, double uc, Point2 u) const;
    double pdf(const Vec3& wo, const Vec3& wi) const;

    /// Whether the GGX lobes apply; otherwise the boundary is a pair of deltas.
    bool rough() const { return alpha > 0 && eta != 1; }
};

/// The course's opaque material made physical: a Lambertian lobe of albedo `diffuse` plus
/// `specular` times a lobe of constant reflectance 1, the perfect mirror (alpha = 0, the
/// course's mirror ray) or the compensated GGX conductor with f0 = 1 (alpha > 0), whose
/// directional albedo is 1 (to the table's error; see Conductor). So the directional albedo is
/// diffuse + specular at every angle and roughness, and energy is conserved when diffuse +
/// specular <= 1 in each channel: a white furnace of diffuse + specular = 1 reflects
/// everything. The lobe sampled is chosen by uc, in proportion to the summed channels of the
/// two colours (and then uc / p is the chosen lobe's own uc).
struct DiffuseSpecular {
    Vec3 diffuse, specular;
    double alpha = 0;  ///< GGX roughness in [0, 1] of the specular lobe.

    Vec3 eval(const Vec3& wo, const Vec3& wi) const;
    std::optional<BsdfSample> sample(const Vec3& wo, double uc, Point2 u) const;
    double pdf(const Vec3& wo, const Vec3& wi) const;

  private:
    double specularProbability() const;
};

/// glTF's layers over its metallic-roughness base (render/bsdfs/pbr_bsdf.cpp), each off by default.
/// KHR_materials_sheen: render/bsdfs/sheen.h's Charlie lobe over the base, which is scaled by what
/// the sheen reflects.
struct SheenLayer {
    Vec3 color{0};                  ///< sheenColor, linear; black: no sheen.
    double alpha = kMinSheenAlpha;  ///< Sheen roughness squared.
};
/// KHR_materials_clearcoat: a clear GGX coat of index 1.5 over everything, with its own
/// roughness and normal, as the specification's fresnel_coat layers it:
///     f = f_base (1 - w F_c) + w F_c D_c G_c / (4 (n_c.o) cos_i)
/// F_c the coat's Schlick reflectance at its normal's cosine with the viewer (not at the
/// half-vector: the specification's choice), w the clearcoat factor. The coat lobe is a GGX
/// lobe about the coat normal n_c divided by the shading cosine cos_i instead of n_c.i, so
/// that the integrator's f |cos_i| is the coat's own f (n_c.i).
struct CoatLayer {
    double weight = 0;     ///< The clearcoat factor; 0: no coat.
    double alpha = 1e-3;   ///< GGX alpha of the coat (its roughness squared).
    Vec3 normal{0, 0, 1};  ///< The coat's normal in the local frame (its own normal map).
};
/// KHR_materials_iridescence: render/bsdfs/thin_film.h's reflectance replaces Schlick's in the
/// dielectric's and the metal's specular lobes, mixed in by the weight.
struct ThinFilmLayer {
    double weight = 0;       ///< The iridescence factor; 0: no film.
    double ior = 1.3;        ///< The film's index.
    double thickness = 400;  ///< Nanometres.
};

/// glTF 2.0's metallic-roughness BRDF as the specification's appendix B defines it, with
/// KHR_materials_transmission and KHR_materials_ior. With h the half-vector of wo and wi,
/// F_d = f0 + (f90 - f0)(1 - |wo.h|)^5 (f0 = ((eta - 1) / (eta + 1))^2, 0.04 for eta 1.5;
/// KHR_materials_specular multiplies f0 by a colour and a factor and sets f90 to the factor),
/// F_m the same with f0 = baseColor and f90 = 1, and S = D G2 / (4 cos_o cos_i) the GGX lobe of
/// alpha (Smith masking separable, as the specification writes it; single scattering, so rough
/// surfaces lose some energy as in the specification and in Cycles' "GGX"):
///     f = (1 - m)(1 - t) [(1 - F_d) diffuse + F_d S] + m F_m S + (1 - m) t f_t
/// m the metalness, t the transmission, and diffuse the Lambertian baseColor / pi, of which
/// KHR_materials_diffuse_transmission sends the share dt through the surface instead
/// (dt diffuseTransmissionColor / pi on the other side, times 1 - F_d at cos_o). f_t, the
/// transmitted part:
///  - thin walls (no KHR_materials_volume): F_d S reflected, and (1 - F_d(cos_o)) baseColor
///    passed straight through (a delta: a thin sheet does not bend light, and its roughness
///    is not modelled);
///  - volumes: the Dielectric of index eta, roughness alpha and tint baseColor (exact Fresnel;
///    the tint colours its reflection too; KHR_materials_specular does not reach it).
/// KHR_materials_anisotropy stretches the reflection lobes' GGX along the local x axis.
/// Sheen and clearcoat layer over that (SheenLayer, CoatLayer), iridescence changes its
/// Fresnel terms (ThinFilmLayer).
/// sample() picks the coat, the sheen, or one of the base's specular, diffuse, diffuse
/// transmission or transmission lobes with probability proportional to its estimated albedo
/// at wo; continuous samples return the whole f and the mixture's density (one-sample MIS).
/// Opaque lobes are two-sided.
struct MetallicRoughness {
    Vec3 baseColor{1};
    double metallic = 0;
    double alpha = 1;  ///< GGX alpha (perceptual roughness squared), at least kMinAlpha.
    double transmission = 0;
    double eta = 1.5;
    bool thin = true;
    double specular = 1;    ///< KHR_materials_specular: the dielectric's f90 and f0 factor.
    Vec3 specularColor{1};  ///< ... and its f0 colour (f0 at most 1 per channel).
    /// KHR_materials_anisotropy's strength in [0, 1]: the GGX alpha along the local x axis is
    /// alpha + (1 - alpha) anisotropy^2 (along y it stays alpha).
    double anisotropy = 0;
    double diffuseTransmission = 0;  ///< KHR_materials_diffuse_transmission's factor.
    Vec3 diffuseTransmissionColor{1};
    /// KHR_materials_dispersion: 20 / the Abbe number; the index of a refracting volume then
    /// varies with the wavelength (etaOfChannel). The path tracer refracts one colour channel
    /// at a time through it (path.cpp).
    double dispersion = 0;
    ThinFilmLayer iridescence{};
    SheenLayer sheen{};
    CoatLayer coat{};

    /// GGX alpha below this is raised to it: the lobe stays a (very narrow) glossy lobe that
    /// light sampling can meet. 1e-3 is a perceptual roughness of 0.03.
    static constexpr double kMinAlpha = 1e-3;

    Vec3 eval(const Vec3& wo, const Vec3& wi) const;
    std::optional<BsdfSample> sample(const Vec3& wo, double uc, Point2 u) const;
    double pdf(const Vec3& wo, const Vec3& wi) const;

    /// Whether light of different colours refracts differently through it.
    bool disperses() const { return dispersion > 0 && !thin && transmission > 0; }
    /// The index at colour channel `c` (0 red, 1 green, 2 blue): the specification's Cauchy
    /// fit through eta at 587.6 nm with Abbe number 20 / dispersion, at 610, 550 and 465 nm,
    /// about the dominant wavelengths of the Rec. 709 primaries.
    double etaOfChannel(int c) const;

  private:
    struct Weights {
        double spec = 0, diffuse = 0, diffuseTrans = 0, trans = 0;
        double sum() const { return spec + diffuse + diffuseTrans + trans; }
    };
    /// The lobes' estimated albedos at o (above the surface), not normalised.
    Weights weights(const Vec3& o) const;
    /// How the layers share the samples at o (wo mirrored when `below`): the coat's, the sheen's
    /// and the base's probabilities, summing to 1 (all 0 if nothing reflects).
    struct LayerChoice {
        double coat = 0, sheen = 0, base = 0;
        double coatFresnel = 0;  ///< w F_c at o.
    };
    LayerChoice layerChoice(const Vec3& o, bool below) const;
    bool layered() const { return coat.weight > 0 || !(sheen.color == Vec3(0)); }
    Vec3 baseEval(const Vec3& wo, const Vec3& wi) const;
    double basePdf(const Vec3& wo, const Vec3& wi) const;
    std::optional<BsdfSample> baseSample(const Vec3& wo, double uc, Point2 u) const;
    /// The dielectric's (F_d) and the metal's (F_m) Fresnel terms at cosine c with the
    /// micro-normal.
    Vec3 dielectricFresnel(double c) const;
    Vec3 metalFresnel(double c) const;
};

/// A BSDF: one of the value structs above.
struct Bsdf {
    std::variant<Lambertian, Conductor, Dielectric, DiffuseSpecular, MetallicRoughness> lobe;

    /// f(wo, wi) in 1 / sr; 0 for delta lobes.
    Vec3 eval(const Vec3& wo, const Vec3& wi) const {
        return std::visit([&](const auto& b) { return b.eval(wo, wi); }, lobe);
    }
    /// A direction wi for `wo` drawn with the uniform numbers `uc` (which lobe) and `u` (where
    /// in it); none if the draw leaves the hemisphere the lobe scatters into, or wo lies in
    /// the surface.
    std::optional<BsdfSample> sample(const Vec3& wo, double uc, Point2 u) const {
        return std::visit([&](const auto& b) { return b.sample(wo, uc, u); }, lobe);
    }
    /// The density (1 / sr) with which sample(wo, ...) draws wi; 0 for delta lobes.
    double pdf(const Vec3& wo, const Vec3& wi) const {
        return std::visit([&](const auto& b) { return b.pdf(wo, wi); }, lobe);
    }
};

/// The BSDF standing for the flat course material `m` (its `diffuse` already replaced by a
/// texture's value where it has one), so that a physically based integrator never gains
/// energy. Colours are clamped to [0, 1] first (the course allows any value); then:
///  - transmission T != 0: Dielectric{ior, T, roughness}, smooth at roughness 0 and GGX
///    above; diffuse and specular are dropped (the dielectric reflects by Fresnel; the
///    course's specular on glass stands in for highlights);
///  - specular S == 0: Lambertian{diffuse};
///  - otherwise DiffuseSpecular{D, S, roughness}, where a channel with D + S > 1 has both
///    divided by D + S.
/// Ambient, emission and shininess are not scattering: integrators take emission from the
/// material itself.
Bsdf bsdfFromMaterial(const Material& m);

}  // namespace glint
