#pragma once
/// The course's opaque material made physical: diffuse plus a mirror or a glossy lobe
/// (bsdf.h's conventions).

#include <iosfwd>
#include <optional>

#include "glint/math/sampling.h"
#include "glint/render/bsdfs/bsdf_sample.h"

namespace glint {

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

    Vec3 eval(const Vec3& wo, const Vec3& wi, TransportMode mode = TransportMode::Radiance) const;
    std::optional<BsdfSample> sample(const Vec3& wo, double uc, Point2 u,
                                     TransportMode mode = TransportMode::Radiance) const;
    double pdf(const Vec3& wo, const Vec3& wi, TransportMode mode = TransportMode::Radiance) const;

    BsdfFlags flags() const {
        return BsdfFlags::Reflection | (diffuse == Vec3(0) ? BsdfFlags::None : BsdfFlags::Diffuse) |
               (alpha == 0 ? BsdfFlags::Specular : BsdfFlags::Glossy);
    }
    std::optional<double> relativeEta() const { return std::nullopt; }
    bool disperses() const { return false; }
    void selectChannel(int) {}
    /// A black mirror shows what it reflects; anything else its colours, summed.
    std::optional<Vec3> passAlbedo() const {
        if (alpha == 0 && diffuse == Vec3(0)) return std::nullopt;
        return min(diffuse + specular, Vec3(1));
    }
    /// A smooth or glossy mirror with no diffuse part.
    bool castsCaustics() const {
        return alpha < kCausticAlpha && diffuse == Vec3(0) && !(specular == Vec3(0));
    }

  private:
    double specularProbability() const;
};

/// Its parameters, for messages and failing tests.
std::ostream& operator<<(std::ostream& out, const DiffuseSpecular& d);

}  // namespace glint
