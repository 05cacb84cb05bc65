#pragma once
/// An emissive box, cylinder, cone or disk as a light (light.h's conventions).

#include <iosfwd>
#include <optional>

#include "glint/geometry/shapes.h"
#include "glint/math/sampling.h"
#include "glint/render/lights/light_sample.h"
#include "glint/render/lights/light_tree.h"

namespace glint {

/// An emissive box, cylinder, cone or disk, transformed as the scene placed it, sampled
/// uniformly over its canonical surface (geometry/surface_sampling.h).
struct ShapeLight {
    const Shape* shape = nullptr;
    Vec3 emission;
    bool frontOnly = false;
    Vec3 lo, hi;     ///< Its bounds,
    double phi = 0;  ///< and its power (pi A L, both sides unless front-only).

    static ShapeLight make(const Shape& shape, const Vec3& lo, const Vec3& hi, const Vec3& emission,
                           bool frontOnly);

    std::optional<LightLiSample> sampleLi(const Vec3& p, Point2 u) const;
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
std::ostream& operator<<(std::ostream& out, const ShapeLight& l);

}  // namespace glint
