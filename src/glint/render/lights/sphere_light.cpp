#include "glint/render/lights/sphere_light.h"

#include <cmath>
#include <ostream>
#include <utility>

#include "glint/geometry/surface_sampling.h"
#include "glint/render/lights/light_util.h"

namespace glint {

using namespace light_util;

namespace {

/// The world centre and radius of sphere `s` if its transform is a similarity (rotation,
/// uniform scale, translation); radius 0 if it is not (an ellipsoid).
std::pair<Vec3, double> roundSphere(const Sphere& s) {
    const Transform& t = s.worldFromObject;
    const Vec3 x = t.vector({1, 0, 0}), y = t.vector({0, 1, 0}), z = t.vector({0, 0, 1});
    const double lx = length(x), ly = length(y), lz = length(z);
    const double tolerance = 1e-9 * lx;
    if (std::abs(lx - ly) > tolerance || std::abs(lx - lz) > tolerance ||
        std::abs(dot(x, y)) > tolerance * lx || std::abs(dot(y, z)) > tolerance * lx ||
        std::abs(dot(z, x)) > tolerance * lx)
        return {Vec3(0), 0};
    return {t.point(s.center), s.radius * lx};
}

/// A round sphere's cone sample from `p` outside it; none from inside or if not round.
std::optional<LightLiSample> sampleCone(const SphereLight& l, const Vec3& p, Point2 u) {
    const Vec3 toCenter = l.center - p;
    const double d2 = dot(toCenter, toCenter);
    if (!outsideSphere(d2, l.radius)) return std::nullopt;
    // A direction within the cone, uniformly: its angle theta from the axis, then the point
    // of the sphere it meets first, by the angle alpha at the centre (pbrt-v4's derivation).
    double sin2Max;
    const double oneMinusCosMax = oneMinusCosCone(l.radius, d2, &sin2Max);
    double cosTheta, sin2Theta;
    if (sin2Max < kSmallCone) {
        sin2Theta = sin2Max * u.x;
        cosTheta = std::sqrt(1 - sin2Theta);
    } else {
        cosTheta = 1 - oneMinusCosMax * u.x;
        sin2Theta = 1 - cosTheta * cosTheta;
    }
    const double cosAlpha = sin2Theta / std::sqrt(sin2Max) +
                            cosTheta * std::sqrt(std::max(1 - sin2Theta / sin2Max, 0.0));
    const double sinAlpha = std::sqrt(std::max(1 - cosAlpha * cosAlpha, 0.0));
    const double phi = 2 * kPi * u.y;
    // The surface normal there, in a frame whose z axis points from the centre to p.
    const Vec3 axis = -toCenter / std::sqrt(d2);
    const Frame frame(axis);
    const Vec3 normal =
        frame.toWorld(Vec3(sinAlpha * std::cos(phi), sinAlpha * std::sin(phi), cosAlpha));
    const Vec3 q = l.center + normal * l.radius;
    const Vec3 d = q - p;
    const double dist = length(d);
    if (!(dist > 0)) return std::nullopt;
    const double pdf = 1 / (2 * kPi * oneMinusCosMax);
    if (!std::isfinite(pdf)) return std::nullopt;
    return LightLiSample{d / dist, l.emission, pdf, 1 / pdf, dist, false};
}

}  // namespace

SphereLight SphereLight::make(const Sphere& sphere, const Vec3& lo, const Vec3& hi,
                              const Vec3& emission, bool frontOnly) {
    SphereLight l;
    l.sphere = &sphere;
    l.emission = emission;
    l.frontOnly = frontOnly;
    std::tie(l.center, l.radius) = roundSphere(sphere);
    l.lo = lo;
    l.hi = hi;
    l.phi = kPi * approximateArea(sphere) * brightness(emission) * (frontOnly ? 1 : 2);
    return l;
}

std::optional<LightLiSample> SphereLight::sampleLi(const Vec3& p, Point2 u) const {
    if (std::optional<LightLiSample> s = sampleCone(*this, p, u)) return s;
    if (outsideSphere(dot(p - center, p - center), radius))
        return std::nullopt;  // from outside, the cone was the way: nothing arrives
    const SurfaceSample ss = sampleSphere(*sphere, u);
    return areaSampleTowards(p, ss.p, ss.n, ss.pdfArea, emission, frontOnly);
}

double SphereLight::pdfLi(const Vec3& from, const LightPoint& at, double choice) const {
    const double d2 = dot(center - from, center - from);
    if (outsideSphere(d2, radius)) {  // sampled by its cone
        double sin2Max;
        return choice / (2 * kPi * oneMinusCosCone(radius, d2, &sin2Max));
    }
    return areaPdfTowards(from, at, spherePdfArea(*sphere, at.n), choice);
}

std::optional<LightLeSample> SphereLight::sampleLe(Point2 uPos, Point2 uDir,
                                                   const LightLeContext& ctx) const {
    const SurfaceSample ss = sampleSphere(*sphere, uPos);
    return fromSurface(ss.p, ss.n, ss.pdfArea, emission, frontOnly, uDir, ctx);
}

LightLePdf SphereLight::pdfLe(const Vec3& origin, const Vec3& n, const Vec3& dir,
                              const LightLeContext& ctx) const {
    return {spherePdfArea(*sphere, n), pdfFromSurface(origin, n, frontOnly, dir, ctx)};
}

std::optional<LightBounds> SphereLight::bounds() const {
    return LightBounds::surface(lo, hi, phi, Vec3(0), !frontOnly);
}

std::ostream& operator<<(std::ostream& out, const SphereLight& l) {
    out << "SphereLight{";
    if (l.radius > 0)
        out << "centre " << l.center << ", radius " << l.radius;
    else
        out << "ellipsoid in " << Bounds3f::enclosing(l.lo, l.hi);
    out << ", emission " << l.emission;
    if (l.frontOnly) out << ", front only";
    return out << "}";
}

}  // namespace glint
