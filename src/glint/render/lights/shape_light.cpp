#include "glint/render/lights/shape_light.h"

#include <ostream>

#include "glint/geometry/surface_sampling.h"
#include "glint/render/lights/light_util.h"

namespace glint {

using namespace light_util;

ShapeLight ShapeLight::make(const Shape& shape, const Vec3& lo, const Vec3& hi,
                            const Vec3& emission, bool frontOnly) {
    ShapeLight l;
    l.shape = &shape;
    l.emission = emission;
    l.frontOnly = frontOnly;
    l.lo = lo;
    l.hi = hi;
    l.phi = kPi * approximateArea(shape) * brightness(emission) * (frontOnly ? 1 : 2);
    return l;
}

std::optional<LightLiSample> ShapeLight::sampleLi(const Vec3& p, Point2 u) const {
    const SurfaceSample ss = sampleShape(*shape, u);
    return areaSampleTowards(p, ss.p, ss.n, ss.pdfArea, emission, frontOnly);
}

double ShapeLight::pdfLi(const Vec3& from, const LightPoint& at, double choice) const {
    return areaPdfTowards(from, at, shapePdfArea(*shape, at.n), choice);
}

std::optional<LightLeSample> ShapeLight::sampleLe(Point2 uPos, Point2 uDir,
                                                  const LightLeContext& ctx) const {
    const SurfaceSample ss = sampleShape(*shape, uPos);
    return fromSurface(ss.p, ss.n, ss.pdfArea, emission, frontOnly, uDir, ctx);
}

LightLePdf ShapeLight::pdfLe(const Vec3& origin, const Vec3& n, const Vec3& dir,
                             const LightLeContext& ctx) const {
    return {shapePdfArea(*shape, n), pdfFromSurface(origin, n, frontOnly, dir, ctx)};
}

std::optional<LightBounds> ShapeLight::bounds() const {
    return LightBounds::surface(lo, hi, phi, Vec3(0), !frontOnly);
}

std::ostream& operator<<(std::ostream& out, const ShapeLight& l) {
    out << "ShapeLight{in " << Bounds3f::enclosing(l.lo, l.hi) << ", emission " << l.emission;
    if (l.frontOnly) out << ", front only";
    return out << "}";
}

}  // namespace glint
