#pragma once
/// Glass: a smooth or rough boundary between two indices of refraction (bsdf.h's conventions).

#include <iosfwd>
#include <optional>

#include "glint/math/sampling.h"
#include "glint/render/bsdfs/bsdf_sample.h"

namespace glint {

/// A boundary between the outside (+z, index 1) and a dielectric of index `eta`, reflecting and
/// transmitting by the exact Fresnel reflectance; `tint` scales both lobes, as the course's
/// `transmission` does. A wo below the surface is a viewer inside: the indices swap.
///  - alpha = 0 (or eta = 1, where nothing bends): smooth, specular reflection and refraction,
///    one chosen with the Fresnel reflectance R as its probability (uc < R reflects), so each
///    weight is `tint` (times the radiance factor of refraction, see below).
///  - alpha > 0: GGX microfacet reflection and transmission after Walter et al., "Microfacet
///    Models for Refraction through Rough Surfaces" (EGSR 2007), as pbrt-v4's DielectricBxDF
///    (there with height-correlated masking; here the separable Smith G1(wo) G1(wi) of the
///    Conductor). With n_o, n_i the indices on wo's and wi's sides and h the microfacet normal
///    (the generalized half-vector n_o wo + n_i wi, turned to +z), F the Fresnel reflectance
///    at wo.h:
///      reflection    f = D(h) G2 F / (4 |cos_o cos_i|)
///      transmission  f = D(h) G2 (1 - F) |wi.h wo.h| / (|cos_o cos_i| (wi.h + wo.h n_o/n_i)^2)
///                        * (n_o / n_i)^2 for radiance (TransportMode), 1 for importance
///    sample() draws h from the normals visible from wo (optics.h), then reflects with
///    probability F and refracts otherwise: the weight is tint G1(wi) times the radiance
///    factor for a transmission. Under total internal reflection at h, F = 1. Single
///    scattering: rays the microsurface would scatter again (reflected below it, refracted
///    back above it) are lost, more of them the rougher the surface.
/// Reciprocity with refraction holds for f / n_o^2: f(wo, wi) / n_o^2 = f(wi, wo) / n_i^2, so
/// the importance f is the adjoint of the radiance f: f_importance(wo, wi) = f_radiance(wi, wo).
struct Dielectric {
    double eta = 1.5;  ///< Index of refraction inside (below the surface) over outside.
    Vec3 tint{1};      ///< Each channel in [0, 1].
    double alpha = 0;  ///< GGX roughness in [0, 1]; 0 is the smooth (delta) boundary.

    Vec3 eval(const Vec3& wo, const Vec3& wi, TransportMode mode = TransportMode::Radiance) const;
    std::optional<BsdfSample> sample(const Vec3& wo, double uc, Point2 u,
                                     TransportMode mode = TransportMode::Radiance) const;
    double pdf(const Vec3& wo, const Vec3& wi, TransportMode mode = TransportMode::Radiance) const;

    /// Whether the GGX lobes apply; otherwise the boundary is a pair of deltas.
    bool rough() const { return alpha > 0 && eta != 1; }

    BsdfFlags flags() const {
        return BsdfFlags::Reflection | BsdfFlags::Transmission |
               (rough() ? BsdfFlags::Glossy : BsdfFlags::Specular);
    }
    /// It bounds a volume of index eta, also at eta 1 (a medium's boundary that bends nothing).
    std::optional<double> relativeEta() const { return eta; }
    bool disperses() const { return false; }
    void selectChannel(int) {}
    /// Smooth glass shows what is seen through it; rough glass its tint.
    std::optional<Vec3> passAlbedo() const {
        return rough() ? std::optional<Vec3>(tint) : std::nullopt;
    }
    bool castsCaustics() const { return alpha < kCausticAlpha; }
};

/// Its parameters, for messages and failing tests.
std::ostream& operator<<(std::ostream& out, const Dielectric& d);

}  // namespace glint
