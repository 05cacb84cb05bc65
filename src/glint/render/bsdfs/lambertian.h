#pragma once
/// Ideal diffuse reflection (bsdf.h's conventions).

#include <iosfwd>
#include <optional>

#include "glint/math/sampling.h"
#include "glint/render/bsdfs/bsdf_sample.h"

namespace glint {

/// Ideal diffuse reflection: f = albedo / pi, sampled with a cosine-weighted density.
struct Lambertian {
    Vec3 albedo;  ///< Directional albedo, each channel in [0, 1].

    Vec3 eval(const Vec3& wo, const Vec3& wi, TransportMode mode = TransportMode::Radiance) const;
    std::optional<BsdfSample> sample(const Vec3& wo, double uc, Point2 u,
                                     TransportMode mode = TransportMode::Radiance) const;
    double pdf(const Vec3& wo, const Vec3& wi, TransportMode mode = TransportMode::Radiance) const;

    BsdfFlags flags() const { return BsdfFlags::Reflection | BsdfFlags::Diffuse; }
    std::optional<double> relativeEta() const { return std::nullopt; }
    bool disperses() const { return false; }
    void selectChannel(int) {}
    std::optional<Vec3> passAlbedo() const { return albedo; }
    bool castsCaustics() const { return false; }
};

/// Its parameters, for messages and failing tests.
std::ostream& operator<<(std::ostream& out, const Lambertian& l);

}  // namespace glint
