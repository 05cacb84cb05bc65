#pragma once
/// Lights: point lights with OpenGL-style attenuation and directional lights (delta lights),
/// and parallelogram area lights. Each is sampled as a Monte Carlo integrator expects, pbrt's
/// way: sampleLi() draws a direction towards the light with the radiance arriving along it and
/// its density, pdfLi() gives that density for any direction.

#include <cmath>
#include <optional>

#include "glint/core/ray.h"
#include "glint/math/sampling.h"

namespace glint {

/// The largest radiance Glint carries (per channel): far above anything a pixel shows, small
/// enough that products of two stay finite, so no Inf (and no 0 * Inf = NaN) ever arises.
constexpr double kMaxRadiance = 1e30;

/// `c` with each channel clamped to +-kMaxRadiance (NaN, which should never occur, to 0).
inline Vec3 finiteRadiance(const Vec3& c) {
    auto clamp = [](double v) {
        return v > -kMaxRadiance ? (v < kMaxRadiance ? v : kMaxRadiance)
                                 : (v == v ? -kMaxRadiance : 0.0);
    };
    return {clamp(c.x), clamp(c.y), clamp(c.z)};
}

/// A direction towards a light drawn by Light::sampleLi, and what arrives along it.
///
/// The density is kept as its reciprocal, `invPdf`, so that the estimator's weight L / pdf is
/// L * invPdf: one rounding, and for quads exactly the course's L * (A cos / r^2) product,
/// which keeps the Whitted integrator's images bit for bit. pdf() gives the density itself
/// (for multiple importance sampling).
struct LightLiSample {
    Vec3 wi;  ///< Unit direction from the shading point towards the light, world space.
    /// Radiance arriving at the point along -wi, before visibility. Delta lights: the colour
    /// over the attenuation (the light's intensity and distance fall-off; a delta in wi).
    Vec3 L;
    /// 1 / pdf, in steradians: for a quad A cos(theta_light) / r^2, the solid angle the whole
    /// light would subtend at the density of this sample; 1 for delta lights (by convention).
    double invPdf = 1;
    double distance = 0;  ///< To the point on the light; infinity for directional lights.

    /// Density of wi over solid angle (1 / sr); 1 for delta lights, by convention.
    double pdf() const { return 1 / invPdf; }
};

struct Light {
    enum class Kind { Point, Directional, Quad };

    Kind kind = Kind::Point;
    Vec3 position;              ///< Point lights; the corner of quad lights. World space.
    Vec3 direction;             ///< Directional lights: unit vector towards the light.
    Vec3 color;                 ///< Point and directional: intensity. Quad: emitted radiance.
    Vec3 attenuation{1, 0, 0};  ///< Constant, linear, quadratic; point lights only.
    /// Quad lights: the parallelogram position + s edge1 + t edge2, s and t in [0, 1]. It emits
    /// from its front face only, the side cross(edge1, edge2) points to.
    Vec3 edge1, edge2;

    bool isArea() const { return kind == Kind::Quad; }
    /// Point and directional lights: a single direction reaches each point, which no BSDF
    /// sample can hit (pdfLi is 0 there).
    bool isDelta() const { return kind != Kind::Quad; }
    /// Quad lights: unit normal of the emitting face and area.
    Vec3 quadNormal() const { return normalize(cross(edge1, edge2)); }
    double quadArea() const { return length(cross(edge1, edge2)); }

    /// A direction from `p` towards the light and the radiance arriving along it, drawn with
    /// `u` in [0, 1)^2 (unused by delta lights). Quads: the point position + u.x edge1 + u.y
    /// edge2, uniform over the area, its density converted to solid angle. None when nothing
    /// arrives for certain: `p` exactly at a point light, or on the plane of a quad or behind
    /// its emitting face. Point lights: an attenuation that rounds to 0 gives the brightest
    /// finite light.
    std::optional<LightLiSample> sampleLi(const Vec3& p, Point2 u) const {
        if (kind == Kind::Point) {
            Vec3 toLight = position - p;
            double d = length(toLight);
            if (!(d > 0)) return std::nullopt;
            double att = attenuation.x + attenuation.y * d + attenuation.z * d * d;
            return LightLiSample{toLight / d, finiteRadiance(color / att), 1, d};
        }
        if (kind == Kind::Directional) return LightLiSample{direction, color, 1, kInfinity};
        return sampleQuad(p, u);
    }

    /// The density over solid angle (1 / sr) with which sampleLi(p, u) draws the unit direction
    /// `wi`, for uniform u: 0 for delta lights, and for directions that miss a quad or meet
    /// its back.
    double pdfLi(const Vec3& p, const Vec3& wi) const {
        if (isDelta()) return 0;
        Vec3 areaNormal = cross(edge1, edge2);  // length = area
        double cosArea = -dot(wi, areaNormal);  // area * cos(theta_light)
        if (!(cosArea > 0)) return 0;
        double distance = dot(p - position, areaNormal) / cosArea;  // along wi to the plane
        if (!(distance > 0)) return 0;
        // Parallelogram coordinates of the point met: q = s edge1 + t edge2.
        Vec3 q = p + wi * distance - position;
        double area2 = dot(areaNormal, areaNormal);
        double s = dot(cross(q, edge2), areaNormal) / area2;
        double t = dot(cross(edge1, q), areaNormal) / area2;
        if (!(s >= 0 && s <= 1 && t >= 0 && t <= 1)) return 0;
        return distance * distance / cosArea;
    }

  private:
    /// sampleLi() for quads. The arithmetic (and so every bit of L * invPdf) is the one the
    /// Whitted integrator has always used: radiance x A cos(theta_light) / r^2.
    std::optional<LightLiSample> sampleQuad(const Vec3& p, Point2 u) const {
        Vec3 toLight = position + edge1 * u.x + edge2 * u.y - p;
        double d2 = dot(toLight, toLight);
        double d = std::sqrt(d2);
        if (!(d > 0)) return std::nullopt;
        Vec3 wi = toLight / d;
        Vec3 areaNormal = cross(edge1, edge2);  // length = area
        double cosArea = -dot(wi, areaNormal);  // area * cos(theta_light)
        if (!(cosArea > 0)) return std::nullopt;
        return LightLiSample{wi, color, cosArea / d2, d};
    }
};

}  // namespace glint
