#pragma once
/// Small helpers the lights share (render/lights/*.cpp): cones of directions towards spheres,
/// and how bright a colour is for weighing lights. Not a public API.

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

#include "glint/core/spawn.h"
#include "glint/math/sampling.h"
#include "glint/math/vec3.h"
#include "glint/render/lights/light_sample.h"

namespace glint::light_util {

constexpr double kPi = std::numbers::pi;

/// Brightness of a colour for weighing lights: its luminance (Rec. 709), or its largest
/// channel if that is not positive (a colour of negative channels).
inline double brightness(const Vec3& c) {
    double y = luminance(c);
    return y > 0 ? y : std::max(maxComponent(c), 0.0);
}

/// Whether a point at squared distance `d2` from the centre of a round sphere of `radius` is
/// outside it, clear of its surface: points on the surface (the inside of an emitting sphere
/// included, whose distance rounds either way) are sampled by area.
inline bool outsideSphere(double d2, double radius) {
    return radius > 0 && d2 > radius * radius * (1 + 1e-6);
}

/// sin^2 of the cone's half-angle below which its cosine is computed from the sine (pbrt-v4:
/// 1.5 degrees), where 1 - cos would lose its digits.
constexpr double kSmallCone = 0.00068523;

/// 1 - cos of the half-angle of the cone that a sphere of `radius` at squared distance `d2`
/// fills; its sine squared in `sin2Max`.
inline double oneMinusCosCone(double radius, double d2, double* sin2Max) {
    *sin2Max = radius * radius / d2;
    return *sin2Max < kSmallCone ? *sin2Max / 2 : 1 - std::sqrt(std::max(1 - *sin2Max, 0.0));
}

/// A direction drawn uniformly over the cone of directions that the sphere (`center`,
/// `radius`) fills from `p`, or over every direction from inside it, and its density.
inline std::pair<Vec3, double> sampleTowardsSphere(const Vec3& p, const Vec3& center, double radius,
                                                   Point2 u) {
    const Vec3 toCenter = center - p;
    const double d2 = dot(toCenter, toCenter);
    if (!outsideSphere(d2, radius)) return {sampleUniformSphere(u), 1 / (4 * kPi)};
    double sin2Max;
    const double oneMinusCos = oneMinusCosCone(radius, d2, &sin2Max);
    const double cosTheta = 1 - u.x * oneMinusCos;
    const double sinTheta = std::sqrt(std::max(0.0, 1 - cosTheta * cosTheta));
    const double phi = 2 * kPi * u.y;
    const Frame frame(toCenter / std::sqrt(d2));
    const Vec3 dir = frame.toWorld({sinTheta * std::cos(phi), sinTheta * std::sin(phi), cosTheta});
    return {normalize(dir), 1 / (2 * kPi * oneMinusCos)};
}

/// The density of sampleTowardsSphere(p, center, radius, u) at unit direction `dir`: 0 outside
/// the cone.
inline double pdfTowardsSphere(const Vec3& p, const Vec3& center, double radius, const Vec3& dir) {
    const Vec3 toCenter = center - p;
    const double d2 = dot(toCenter, toCenter);
    if (!outsideSphere(d2, radius)) return 1 / (4 * kPi);
    double sin2Max;
    const double oneMinusCos = oneMinusCosCone(radius, d2, &sin2Max);
    const double cosTheta = dot(dir, toCenter) / std::sqrt(d2);
    return cosTheta >= 1 - oneMinusCos ? 1 / (2 * kPi * oneMinusCos) : 0;
}

/// The solid angle the sphere fills from `p` (4 pi from inside).
inline double solidAngleOfSphere(const Vec3& p, const Vec3& center, double radius) {
    const double d2 = dot(center - p, center - p);
    if (!outsideSphere(d2, radius)) return 4 * kPi;
    double sin2Max;
    return 2 * kPi * oneMinusCosCone(radius, d2, &sin2Max);
}

/// A ray of a light at infinity whose light arrives from unit direction `towards` with
/// `radiance` and direction density `pdfDir` (1 for a delta): across the target's disc
/// uniformly (density 1 / (pi r^2)), from `far` beyond its centre.
inline LightLeSample acrossDisc(const Vec3& towards, const Vec3& radiance, double pdfDir,
                                Point2 uPos, const LightLeContext& ctx) {
    const auto [dx, dy] = sampleUniformDisk(uPos.x, uPos.y);
    const Frame frame(towards);
    const Vec3 origin = ctx.center + towards * ctx.far + (frame.t * dx + frame.b * dy) * ctx.radius;
    const double area = kPi * ctx.radius * ctx.radius;
    return LightLeSample{Ray{origin, -towards, 0, kInfinity}, origin,   Vec3(0), radiance,
                         radiance * (area / pdfDir),          1 / area, pdfDir,  std::nullopt};
}

/// A ray from point `p` of a surface of unit normal `n`, emitting `radiance` (from its front
/// only if `frontOnly`), drawn with position density `pdfPos` (over area) and a direction
/// into the target's cone, and started off the surface; none if it leaves by a face that does
/// not emit.
inline std::optional<LightLeSample> fromSurface(const Vec3& p, const Vec3& n, double pdfPos,
                                                const Vec3& radiance, bool frontOnly, Point2 uDir,
                                                const LightLeContext& ctx) {
    if (!(pdfPos > 0)) return std::nullopt;
    const auto [dir, pdfDir] = sampleTowardsSphere(p, ctx.center, ctx.radius, uDir);
    const double cosLight = dot(dir, n);
    if (frontOnly ? !(cosLight > 0) : cosLight == 0) return std::nullopt;
    const Vec3 beta = radiance * (std::abs(cosLight) / (pdfPos * pdfDir));
    return LightLeSample{spawnRayOffSurface(p, n, dir, ctx.offset),
                         p,
                         n,
                         radiance,
                         beta,
                         pdfPos,
                         pdfDir,
                         std::nullopt};
}

/// fromSurface's direction density for a ray leaving `p` (normal `n`) along `dir`.
inline double pdfFromSurface(const Vec3& p, const Vec3& n, bool frontOnly, const Vec3& dir,
                             const LightLeContext& ctx) {
    const double cosLight = dot(dir, n);
    if (frontOnly ? !(cosLight > 0) : cosLight == 0) return 0;
    return pdfTowardsSphere(p, ctx.center, ctx.radius, dir);
}

/// The direction from `p` to the point `q` (unit normal `n`) drawn on a surface with density
/// `pdfArea` over area, which emits `radiance` (from its front only if `frontOnly`): its
/// density converted to solid angle, pdfArea d^2 / |cos theta_light|. None if the point does not
/// face `p` or the density is not finite.
inline std::optional<LightLiSample> areaSampleTowards(const Vec3& p, const Vec3& q, const Vec3& n,
                                                      double pdfArea, const Vec3& radiance,
                                                      bool frontOnly) {
    Vec3 d = q - p;
    double d2 = dot(d, d);
    if (!(d2 > 0)) return std::nullopt;
    double dist = std::sqrt(d2);
    Vec3 wi = d / dist;
    double cosLight = dot(wi, n);  // < 0: the sample faces p
    if (frontOnly ? !(cosLight < 0) : cosLight == 0) return std::nullopt;
    double pdf = pdfArea * d2 / std::abs(cosLight);
    if (!(pdf > 0) || !std::isfinite(pdf)) return std::nullopt;
    return LightLiSample{wi, radiance, pdf, 1 / pdf, dist, false};
}

/// choice times the density over solid angle, seen from `from`, of a point `at` of a surface
/// drawn with density `pdfArea` over area.
inline double areaPdfTowards(const Vec3& from, const LightPoint& at, double pdfArea,
                             double choice) {
    Vec3 d = at.p - from;
    double d2 = dot(d, d);
    double cosLight = std::abs(dot(d, at.n)) / std::sqrt(d2);
    if (!(cosLight > 0)) return 0;
    return choice * pdfArea * d2 / cosLight;
}

}  // namespace glint::light_util
