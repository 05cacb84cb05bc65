#pragma once
/// Bidirectional scattering distribution functions (BSDFs) for a physically based integrator,
/// in lajolla's style: `Bsdf` holds one of a few small value structs, the lobes, each in a file
/// of its own in this folder, dispatched through a std::variant without allocation or virtual
/// calls. Integrators ask the `Bsdf` (its value, a direction, a density, and the questions
/// below), never which lobe it holds.
///
/// Conventions (pbrt-v4's). Everything is in a local shading frame whose normal is +z; wo and
/// wi are unit directions pointing away from the surface (wo towards the viewer or where the
/// path came from, wi towards the light or where it goes next).
///  - eval(wo, wi) is f, in 1 / sr; the integrand is f |cos theta_i| L_i.
///  - sample(wo, uc, u) draws wi with density pdf (1 / sr) and returns f there: f |cos| / pdf
///    is the estimator's weight. Delta lobes (perfect mirrors and refraction) have no density:
///    eval() and pdf() are 0 for them, and sample() returns f and pdf as the delta's
///    coefficients (the discrete probability of choosing that lobe), whose ratio is still the
///    weight.
///  - Transport (bsdf_sample.h's TransportMode): radiance for paths from the camera (the
///    default), importance for paths from the lights (render/integrators/caustics.h). They
///    differ by the (n_o / n_i)^2 that refraction applies to radiance only.
///  - Opaque lobes are two-sided: a wo below the surface sees the mirror image of the lobe.
///
/// The Whitted integrator does not use these: the course's Blinn-Phong term is not a BSDF.

#include <iosfwd>
#include <optional>
#include <variant>

#include "glint/math/sampling.h"
#include "glint/math/vec3.h"
#include "glint/render/bsdfs/bsdf_sample.h"
#include "glint/render/bsdfs/conductor.h"
#include "glint/render/bsdfs/dielectric.h"
#include "glint/render/bsdfs/diffuse_specular.h"
#include "glint/render/bsdfs/lambertian.h"
#include "glint/render/bsdfs/metallic_roughness.h"
#include "glint/scene/material.h"

namespace glint {

/// A BSDF: one lobe of the variant below.
///
/// A new lobe is a struct in a file of its own here (NAME.h, NAME.cpp), added to `Lobe`; a
/// material that maps to it does so in bsdfFromMaterial() (the course's materials) or in
/// render/integrators/surface_shading.cpp (glTF's). It must provide, or the variant does not
/// compile:
///  - `Vec3 eval(wo, wi, TransportMode)`, `std::optional<BsdfSample> sample(wo, uc, u,
///    TransportMode)` and `double pdf(wo, wi, TransportMode)`, with the conventions above: a
///    lobe that refracts scales radiance, not importance, by (n_o / n_i)^2;
///  - `BsdfFlags flags()`: which of reflection and transmission, diffuse, glossy and specular
///    it can do (the path tracer samples no light for a lobe with neither diffuse nor glossy
///    parts, and weighs lights from both sides of one that transmits);
///  - `std::optional<double> relativeEta()`: the index of refraction inside over outside when
///    light crossing it refracts into a volume (glass: its surface then bounds a medium);
///    none for an opaque surface or a thin wall;
///  - `bool disperses()` and `void selectChannel(int c)`: whether its index depends on the
///    wavelength, and the lobe as light of colour channel c sees it;
///  - `std::optional<Vec3> passAlbedo()`: the albedo the render passes show for it (film.h),
///    none where they look through it to what it reflects or transmits (a perfect mirror,
///    smooth glass);
///  - `bool castsCaustics()`: whether it focuses light sharply enough (a smooth or glossy
///    mirror, metal or glass) for the light pass to trace what reaches a surface through it;
///  - `operator<<` (its parameters, for messages and failing tests), and chi-square, furnace (and,
///  if it transmits,
///    adjoint) cases in tests/unit/render/bsdfs/.
class Bsdf {
  public:
    using Lobe =
        std::variant<Lambertian, Conductor, Dielectric, DiffuseSpecular, MetallicRoughness>;

    Bsdf() = default;
    /// The BSDF of one lobe.
    template <typename L>
    requires std::is_constructible_v<Lobe, L> Bsdf(L lobe) : lobe_(std::move(lobe)) {}

    /// f(wo, wi) in 1 / sr; 0 for delta lobes.
    Vec3 eval(const Vec3& wo, const Vec3& wi, TransportMode mode = TransportMode::Radiance) const {
        return std::visit([&](const auto& b) { return b.eval(wo, wi, mode); }, lobe_);
    }
    /// A direction wi for `wo` drawn with the uniform numbers `uc` (which lobe) and `u` (where
    /// in it); none if the draw leaves the hemisphere the lobe scatters into, or wo lies in
    /// the surface.
    std::optional<BsdfSample> sample(const Vec3& wo, double uc, Point2 u,
                                     TransportMode mode = TransportMode::Radiance) const {
        return std::visit([&](const auto& b) { return b.sample(wo, uc, u, mode); }, lobe_);
    }
    /// The density (1 / sr) with which sample(wo, ...) draws wi; 0 for delta lobes.
    double pdf(const Vec3& wo, const Vec3& wi, TransportMode mode = TransportMode::Radiance) const {
        return std::visit([&](const auto& b) { return b.pdf(wo, wi, mode); }, lobe_);
    }

    /// What kinds of scattering it can do.
    BsdfFlags flags() const {
        return std::visit([](const auto& b) { return b.flags(); }, lobe_);
    }
    /// Whether every lobe is a delta (no diffuse or glossy part): no light sample can meet it.
    bool specularOnly() const { return !hasAny(flags(), BsdfFlags::Diffuse | BsdfFlags::Glossy); }
    /// Whether light can pass through it: light reaches it from both sides.
    bool transmits() const { return hasAny(flags(), BsdfFlags::Transmission); }
    /// Inside over outside, if light crossing it refracts into a volume.
    std::optional<double> relativeEta() const {
        return std::visit([](const auto& b) { return b.relativeEta(); }, lobe_);
    }
    /// Whether light of different colours refracts differently through it.
    bool disperses() const {
        return std::visit([](const auto& b) { return b.disperses(); }, lobe_);
    }
    /// The BSDF as light of colour channel `c` (0 red, 1 green, 2 blue) alone sees it.
    void selectChannel(int c) {
        std::visit([c](auto& b) { b.selectChannel(c); }, lobe_);
    }
    /// The albedo the render passes show for it; none where they follow a delta lobe on.
    std::optional<Vec3> passAlbedo() const {
        return std::visit([](const auto& b) { return b.passAlbedo(); }, lobe_);
    }
    /// Whether it focuses light into caustics (render/integrators/caustics.h).
    bool castsCaustics() const {
        return std::visit([](const auto& b) { return b.castsCaustics(); }, lobe_);
    }

    /// The lobe, if it is an `L`: for tests of the mapping from materials, and for printing.
    /// Integrators ask the questions above instead.
    template <typename L>
    const L* as() const {
        return std::get_if<L>(&lobe_);
    }

    /// "Dielectric{eta 1.5, tint (1, 1, 1), alpha 0}": its lobe's parameters.
    friend std::ostream& operator<<(std::ostream& out, const Bsdf& bsdf);

  private:
    Lobe lobe_;
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
