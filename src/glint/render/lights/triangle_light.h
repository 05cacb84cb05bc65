#pragma once
/// An emissive triangle as a light (light.h's conventions).

#include <iosfwd>
#include <optional>

#include "glint/geometry/primitives.h"
#include "glint/math/sampling.h"
#include "glint/render/lights/light_sample.h"
#include "glint/render/lights/light_tree.h"
#include "glint/scene/pbr_material.h"

namespace glint {

/// An emissive triangle of the scene, or of a mesh an instance places (one light per
/// placement), possibly with an emissive texture. Seen from a point, it is sampled uniformly
/// over the solid angle it fills (Arvo 1995: math/spherical_triangle.h) unless it is tiny or
/// nearly a hemisphere there, then uniformly by area; light paths leave it from a point drawn
/// by area.
struct TriangleLight {
    /// The corner c, the edges a - c and b - c (world space), and the unit normal of
    /// cross(b - a, c - a): a point is c + (a - c) b0 + (b - c) b1.
    Vec3 c, ca, cb, n;
    double pdfArea = 0;      ///< 1 / area.
    Vec3 emission;           ///< Its radiance (textured: the material's factor).
    bool frontOnly = false;  ///< Quad lights' triangles emit from their front face only.
    /// An emissive texture: the material, and the mesh and triangle to look its coordinates
    /// up in (the scene's primitives, or an instanced mesh in its own space).
    const PbrMaterial* texture = nullptr;
    const Primitives* mesh = nullptr;
    uint32_t triangle = 0;
    Vec3 lo, hi;     ///< The world corners' bounds,
    double phi = 0;  ///< and its power, for the light tree.

    /// The light for the world corners va, vb, vc, with `emission` and `frontOnly` as a
    /// material gives them; none if it has no area. Its power is pi A L (twice that if both
    /// faces emit), L the emission's brightness, or for a texture its mean estimated at four
    /// points (the centroid and halfway from there to each corner); none if that is 0 (a
    /// texture black there: a ray that finds it counts its light in full).
    static std::optional<TriangleLight> make(const Vec3& va, const Vec3& vb, const Vec3& vc,
                                             const Vec3& emission, bool frontOnly,
                                             const PbrMaterial* texture, const Primitives* mesh,
                                             uint32_t triangle);

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

    /// The emission at barycentrics (b1, b2) of its b and c corners.
    Vec3 emissionAt(double b1, double b2) const;
};
std::ostream& operator<<(std::ostream& out, const TriangleLight& l);

}  // namespace glint
