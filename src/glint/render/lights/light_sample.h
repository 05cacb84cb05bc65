#pragma once
/// What every light (render/lights/) shares: the direction it draws towards a point
/// (LightLiSample), the point of it a ray found (LightPoint), the ray it sends out for a light
/// path (LightLeSample) and the densities of such rays (LightLePdf). The conventions are in
/// light.h, beside the variant of lights.

#include <iosfwd>
#include <optional>

#include "glint/core/ray.h"
#include "glint/math/vec3.h"

namespace glint {

/// A direction towards a light drawn by sampleLi, and what arrives along it.
struct LightLiSample {
    Vec3 wi;  ///< Unit direction from the shading point towards the light, world space.
    /// Radiance arriving at the point along -wi, before visibility. Delta lights: the colour
    /// over the attenuation (the light's intensity and distance fall-off; a delta in wi).
    Vec3 L;
    /// Density of wi over solid angle (1 / sr); 1 for delta lights, by convention.
    double pdf = 1;
    /// 1 / pdf as the light computed it: for quads A cos(theta_light) / r^2, so that L * invPdf
    /// is the course's L A cos / r^2 to the bit (L / pdf differs in the last bit for about a
    /// quarter of samples); 1 for delta lights.
    double invPdf = 1;
    double distance = 0;  ///< To the point on the light; infinity for lights at infinity.
    bool delta = false;   ///< A point, spot or directional light: no BSDF sample can reach it.
};
/// "LightLiSample{wi (..), L (..), pdf p, distance d}" (", delta" for delta lights).
std::ostream& operator<<(std::ostream& out, const LightLiSample& s);

/// A point of a light that a ray from elsewhere reached: where, the unit geometric normal
/// there, and the ray's unit direction. Lights at infinity read the direction only.
struct LightPoint {
    Vec3 p, n, wi;
};

/// Where the rays of a light path are aimed: the sphere of `center` and `radius` that holds
/// what the path is for (the light pass's: the surfaces that cast caustics). Bounded lights send
/// rays into its cone of directions; lights at infinity across its disc, from `far` beyond
/// its centre (outside the scene). Rays leave surfaces `offset` off them (Scene::spawnOffset).
struct LightLeContext {
    Vec3 center;
    double radius = 1;
    double far = 1;
    double offset = 0;
};

/// A ray leaving a light, for a path traced from it (sampleLe).
struct LightLeSample {
    /// From the light's surface (started just off it), or from outside the scene for lights
    /// at infinity.
    Ray ray;
    Vec3 p;  ///< The point the ray leaves the light from (on its surface; the ray's origin else).
    Vec3 n;  ///< The light's unit normal at p; zero for points and at infinity.
    Vec3 L;  ///< Radiance (points: intensity) the light emits along the ray.
    /// L |cos| / (pdfPos pdfDir) (delta densities as their coefficients, 1): the flux the
    /// ray carries, in the units of a path's throughput.
    Vec3 beta;
    /// Density of the origin: over the light's area, or over the target's disc for lights at
    /// infinity; 1 for a point (a delta).
    double pdfPos = 1;
    /// Density of the direction over solid angle; 1 for a directional light (a delta).
    double pdfDir = 1;
    /// A point or spot light with the course's attenuation (constant, linear, quadratic): beta
    /// is still to be multiplied by d^2 / attenuation(d), d the distance to the first surface
    /// the ray meets.
    std::optional<Vec3> attenuation;
};

/// "LightLeSample{Ray{...}, L (..), beta (..), pdfPos p, pdfDir d}".
std::ostream& operator<<(std::ostream& out, const LightLeSample& s);

/// The densities with which sampleLe draws a ray (pdfLe); delta densities are 0, as a BSDF's
/// pdf() is for its delta lobes.
struct LightLePdf {
    double pos = 0, dir = 0;
};

}  // namespace glint
