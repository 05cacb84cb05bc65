#include "glint/render/lights/triangle_light.h"

#include <cmath>
#include <ostream>

#include "glint/math/spherical_triangle.h"
#include "glint/render/lights/light_util.h"

namespace glint {

using namespace light_util;

namespace {

/// The triangle seen from `p`: the unit directions to its corners, and the solid angle it
/// fills where it is sampled by solid angle (neither tiny nor nearly a hemisphere); 0 where it
/// is sampled by area.
struct SphericalTriangle {
    Vec3 a, b, c;
    double solidAngle = 0;
};

SphericalTriangle sphericalTriangle(const TriangleLight& l, const Vec3& p) {
    // pbrt-v4's range: below, the triangle is small or far enough that area sampling is as
    // good and the spherical construction loses digits; above, nearly a hemisphere.
    constexpr double kMin = 3e-4, kMax = 6.22;
    const Vec3 a = l.c + l.ca - p, b = l.c + l.cb - p, c = l.c - p;
    const double la = length(a), lb = length(b), lc = length(c);
    if (!(la > 0 && lb > 0 && lc > 0)) return {};
    SphericalTriangle t{a / la, b / lb, c / lc, 0};
    const double area = sphericalTriangleArea(t.a, t.b, t.c);
    if (area >= kMin && area <= kMax) t.solidAngle = area;
    return t;
}

}  // namespace

std::optional<TriangleLight> TriangleLight::make(const Vec3& va, const Vec3& vb, const Vec3& vc,
                                                 const Vec3& emission, bool frontOnly,
                                                 const PbrMaterial* texture, const Primitives* mesh,
                                                 uint32_t triangle) {
    TriangleLight l;
    const Vec3 cr = cross(vb - va, vc - va);
    const double area = 0.5 * length(cr);
    if (!(area > 0)) return std::nullopt;
    l.pdfArea = 1 / area;
    l.c = vc;
    l.ca = va - vc;
    l.cb = vb - vc;
    l.n = cr / (2 * area);
    l.lo = min(va, min(vb, vc));
    l.hi = max(va, max(vb, vc));
    l.emission = emission;
    l.frontOnly = frontOnly;
    l.texture = texture;
    l.mesh = mesh;
    l.triangle = triangle;
    // A textured emitter's power is its own triangle's, the texture's mean over it estimated
    // at its centroid and halfway from there to each corner (an emissive map is mostly black:
    // most of a mesh's triangles emit nothing, and leave the tree).
    double radiance = brightness(emission);
    if (texture) {
        constexpr double kAt[4][2] = {
            {1.0 / 3, 1.0 / 3}, {2.0 / 3, 1.0 / 6}, {1.0 / 6, 2.0 / 3}, {1.0 / 6, 1.0 / 6}};
        double sum = 0;
        for (const auto& at : kAt) sum += brightness(l.emissionAt(at[0], at[1]));
        radiance = sum / 4;
    }
    l.phi = kPi * area * radiance * (frontOnly ? 1 : 2);
    if (!(l.phi > 0)) return std::nullopt;
    return l;
}

Vec3 TriangleLight::emissionAt(double b1, double b2) const {
    if (!texture) return emission;
    return glint::emissionAt(*texture, mesh->triangleAttributes(triangle, b1, b2));
}

std::optional<LightLiSample> TriangleLight::sampleLi(const Vec3& p, Point2 u) const {
    if (const SphericalTriangle t = sphericalTriangle(*this, p); t.solidAngle > 0) {
        // Uniformly within the solid angle.
        const std::optional<Vec3> wi = sampleSphericalTriangle(t.a, t.b, t.c, u);
        if (!wi) return std::nullopt;
        const double cosLight = dot(*wi, n);  // < 0: the light's front faces p
        if (frontOnly ? !(cosLight < 0) : cosLight == 0) return std::nullopt;
        const double dist = dot(c - p, n) / cosLight;  // to the triangle's plane
        if (!(dist > 0) || !std::isfinite(dist)) return std::nullopt;
        Vec3 radiance = emission;
        if (texture) {  // the point's barycentrics: of a (b0) and of b (b1)
            const Vec3 q = p + *wi * dist - c;
            const double twiceArea = 2 / pdfArea;
            const double b0 = dot(cross(q, cb), n) / twiceArea;
            const double b1 = dot(cross(ca, q), n) / twiceArea;
            radiance = emissionAt(b1, 1 - b0 - b1);
        }
        const double pdf = 1 / t.solidAngle;
        return LightLiSample{*wi, radiance, pdf, t.solidAngle, dist, false};
    }
    auto [b0, b1] = sampleUniformTriangle(u);  // as sampleTriangle, from stored edges
    const Vec3 q = c + ca * b0 + cb * b1;
    // The point is a b0 + b b1 + c (1 - b0 - b1).
    const Vec3 radiance = texture ? emissionAt(b1, 1 - b0 - b1) : emission;
    return areaSampleTowards(p, q, n, pdfArea, radiance, frontOnly);
}

double TriangleLight::pdfLi(const Vec3& from, const LightPoint& at, double choice) const {
    if (const double solidAngle = sphericalTriangle(*this, from).solidAngle; solidAngle > 0)
        return choice / solidAngle;
    return areaPdfTowards(from, at, pdfArea, choice);
}

std::optional<LightLeSample> TriangleLight::sampleLe(Point2 uPos, Point2 uDir,
                                                     const LightLeContext& ctx) const {
    auto [b0, b1] = sampleUniformTriangle(uPos);
    const Vec3 q = c + ca * b0 + cb * b1;
    const Vec3 radiance = texture ? emissionAt(b1, 1 - b0 - b1) : emission;
    return fromSurface(q, n, pdfArea, radiance, frontOnly, uDir, ctx);
}

LightLePdf TriangleLight::pdfLe(const Vec3& origin, const Vec3&, const Vec3& dir,
                                const LightLeContext& ctx) const {
    return {pdfArea, pdfFromSurface(origin, n, frontOnly, dir, ctx)};
}

std::optional<LightBounds> TriangleLight::bounds() const {
    return LightBounds::surface(lo, hi, phi, n, !frontOnly);
}

std::ostream& operator<<(std::ostream& out, const TriangleLight& l) {
    out << "TriangleLight{corners " << l.c + l.ca << ", " << l.c + l.cb << ", " << l.c
        << ", emission " << l.emission;
    if (l.texture) out << " (textured)";
    if (l.frontOnly) out << ", front only";
    return out << "}";
}

}  // namespace glint
