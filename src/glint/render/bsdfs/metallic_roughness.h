#pragma once
/// glTF's metallic-roughness material and its layers as one BSDF lobe (bsdf.h's conventions).

#include <iosfwd>
#include <optional>

#include "glint/math/sampling.h"
#include "glint/render/bsdfs/bsdf_sample.h"
#include "glint/render/bsdfs/sheen.h"

namespace glint {

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
    /// GGX alpha below which a mirror-like or glass-like surface counts as smooth for the render
    /// passes (a perceptual roughness of 0.1): they follow it to what is seen in it.
    static constexpr double kPassSmoothAlpha = 0.01;

    Vec3 eval(const Vec3& wo, const Vec3& wi, TransportMode mode = TransportMode::Radiance) const;
    std::optional<BsdfSample> sample(const Vec3& wo, double uc, Point2 u,
                                     TransportMode mode = TransportMode::Radiance) const;
    double pdf(const Vec3& wo, const Vec3& wi, TransportMode mode = TransportMode::Radiance) const;

    /// Glossy reflection always (the specular lobe, sheen, coat), diffuse where the base is not
    /// all metal or glass, transmission with either transmission, specular for a thin wall's
    /// (or an index-1 volume's) straight-through delta.
    BsdfFlags flags() const;
    /// A volume (not thin) that transmits refracts into it.
    std::optional<double> relativeEta() const {
        return !thin && transmission > 0 ? std::optional<double>(eta) : std::nullopt;
    }
    /// Whether light of different colours refracts differently through it.
    bool disperses() const { return dispersion > 0 && !thin && transmission > 0; }
    /// A dispersing volume takes the index of colour channel `c` (etaOfChannel).
    void selectChannel(int c) {
        if (disperses()) eta = etaOfChannel(c);
    }
    /// The index at colour channel `c` (0 red, 1 green, 2 blue): the specification's Cauchy
    /// fit through eta at 587.6 nm with Abbe number 20 / dispersion, at 610, 550 and 465 nm,
    /// about the dominant wavelengths of the Rec. 709 primaries.
    double etaOfChannel(int c) const;
    /// The base colour, but none for a surface nearly as smooth as a mirror (GGX alpha below
    /// kPassSmoothAlpha) that is all metal or clear glass: the passes show what it reflects or
    /// lets through.
    std::optional<Vec3> passAlbedo() const {
        if (alpha < kPassSmoothAlpha && clearness() > 0.99) return std::nullopt;
        return baseColor;
    }
    /// All metal or clear glass (at most 1% diffuse), smooth or glossy.
    bool castsCaustics() const { return clearness() > 0.99 && alpha < kCausticAlpha; }

  private:
    /// The share of the base that is metal or transmission, not diffuse.
    double clearness() const { return metallic + (1 - metallic) * transmission; }
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
    Vec3 baseEval(const Vec3& wo, const Vec3& wi, TransportMode mode) const;
    double basePdf(const Vec3& wo, const Vec3& wi) const;
    std::optional<BsdfSample> baseSample(const Vec3& wo, double uc, Point2 u,
                                         TransportMode mode) const;
    /// The dielectric's (F_d) and the metal's (F_m) Fresnel terms at cosine c with the
    /// micro-normal.
    Vec3 dielectricFresnel(double c) const;
    Vec3 metalFresnel(double c) const;
};

/// Its parameters, for messages and failing tests.
std::ostream& operator<<(std::ostream& out, const MetallicRoughness& m);

}  // namespace glint
