#pragma once
/// Light in participating media (scene/medium.h), for the path tracer: where along a ray a
/// medium scatters, how much of the light it lets through, and the Henyey-Greenstein phase
/// function that scatters there.
///
/// Sampling is delta tracking against a majorant (Woodcock; pbrt-v4's "null scattering"):
/// tentative collisions are drawn at the rate sigma_maj, a bound on the extinction (the
/// homogeneous sigma_t's largest channel; in a grid, it times the largest density of each
/// block of the majorant grid the ray crosses, scene/medium.h, stepped through block by block),
/// and each is a real scattering, an absorption or a null collision. Colours differ per channel, so
/// the event is chosen by the channels' mean probabilities and the throughput takes the ratio of
/// each channel's coefficient to that probability (spectral tracking, Kutz et al. 2017,
/// without its hero wavelength): unbiased in every channel, and exact for grey media.
/// Transmittance along shadow rays is exact for homogeneous media and ratio tracking (Novak et
/// al. 2014) through grids.

#include <optional>

#include "glint/core/ray.h"
#include "glint/math/rng.h"
#include "glint/math/sampling.h"
#include "glint/math/vec3.h"
#include "glint/scene/medium.h"

namespace glint {

/// The Henyey-Greenstein phase function of asymmetry g: p(cos) = (1 - g^2) /
/// (4 pi (1 + g^2 - 2 g cos)^(3/2)), cos the cosine between the direction light travels on and
/// the direction it continues in (g > 0 scatters forwards). Normalised over the sphere.
struct HenyeyGreenstein {
    double g = 0;

    /// The density for light arriving along -wo (wo points back towards where the path came
    /// from) and leaving towards wi; unit vectors.
    double eval(const Vec3& wo, const Vec3& wi) const;
    /// A direction wi drawn with density eval(wo, wi).
    Vec3 sample(const Vec3& wo, Point2 u) const;
};

/// What a medium did to a path along a segment.
struct MediumEvent {
    enum class Kind { Passed, Scattered, Absorbed } kind = Kind::Passed;
    double t = 0;  ///< Where it scattered (ray parameter).
};

/// Samples the medium `m` along `ray` (its direction need not be unit) over [0, tEnd): the
/// first real collision, with `beta` (the path's throughput) multiplied by the estimator's
/// weights; Passed when the path reaches tEnd (tEnd may be infinite only if the medium's
/// extinction is above 0 everywhere along the ray, as a homogeneous fog's).
MediumEvent sampleMedium(const Medium& m, const Ray& ray, double tEnd, Rng& rng, Vec3& beta);

/// The fraction of light the medium `m` lets through along `ray` over [0, tEnd): exp of the
/// optical depth when homogeneous, ratio tracking through a grid (unbiased, random).
Vec3 mediumTransmittance(const Medium& m, const Ray& ray, double tEnd, Rng& rng);

}  // namespace glint
