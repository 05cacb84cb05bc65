#pragma once
/// The course's parallelogram area light, for the Whitted integrator (light.h's conventions).

#include <cmath>
#include <iosfwd>
#include <optional>

#include "glint/math/sampling.h"
#include "glint/render/lights/light_sample.h"
#include "glint/render/lights/light_tree.h"

namespace glint {

/// A parallelogram position + s edge1 + t edge2 (s, t in [0, 1]) of uniform radiance `color`,
/// emitting from its front face (the side cross(edge1, edge2) points to) only. sampleLi draws
/// a point uniformly by area, its density converted to solid angle, with the arithmetic the
/// course's renderer used: every bit of L * invPdf is its L A cos / r^2. The Whitted
/// integrator samples these; the path tracer samples the emissive triangles the scene builder
/// made of the same quad (TriangleLight).
struct QuadLight {
    Vec3 position, edge1, edge2;
    Vec3 color;

    /// None when nothing arrives for certain: `p` on the plane of the quad or behind its
    /// emitting face. Inline: the Whitted integrator's inner loop.
    std::optional<LightLiSample> sampleLi(const Vec3& p, Point2 u) const {
        // The arithmetic (and so every bit of L * invPdf) is the one the Whitted integrator
        // has always used: radiance x A cos(theta_light) / r^2.
        Vec3 toLight = position + edge1 * u.x + edge2 * u.y - p;
        double d2 = dot(toLight, toLight);
        double d = std::sqrt(d2);
        if (!(d > 0)) return std::nullopt;
        Vec3 wi = toLight / d;
        Vec3 areaNormal = cross(edge1, edge2);  // length = area
        double cosArea = -dot(wi, areaNormal);  // area * cos(theta_light)
        if (!(cosArea > 0)) return std::nullopt;
        const double invPdf = cosArea / d2;
        return LightLiSample{wi, color, 1 / invPdf, invPdf, d, false};
    }
    double pdfLi(const Vec3& from, const LightPoint& at, double choice = 1) const;
    std::optional<LightLeSample> sampleLe(Point2 uPos, Point2 uDir,
                                          const LightLeContext& ctx) const;
    LightLePdf pdfLe(const Vec3& origin, const Vec3& n, const Vec3& dir,
                     const LightLeContext& ctx) const;
    std::optional<LightBounds> bounds() const;
    double infiniteImportance() const { return 0; }
    double lightPassShare() const { return 1; }
    bool tracedByLightPass(const Vec3&) const { return true; }
    bool isDelta() const { return false; }
};
std::ostream& operator<<(std::ostream& out, const QuadLight& l);

}  // namespace glint
