#include "glint/render/lights/quad_light.h"

#include <cmath>
#include <ostream>

#include "glint/render/lights/light_util.h"

namespace glint {

using namespace light_util;

double QuadLight::pdfLi(const Vec3& from, const LightPoint& at, double choice) const {
    // By the direction alone: where it meets the parallelogram, if it does.
    const Vec3& wi = at.wi;
    Vec3 areaNormal = cross(edge1, edge2);  // length = area
    double cosArea = -dot(wi, areaNormal);  // area * cos(theta_light)
    if (!(cosArea > 0)) return 0;
    double distance = dot(from - position, areaNormal) / cosArea;  // along wi to the plane
    if (!(distance > 0)) return 0;
    // Parallelogram coordinates of the point met: q = s edge1 + t edge2.
    Vec3 q = from + wi * distance - position;
    double area2 = dot(areaNormal, areaNormal);
    double s = dot(cross(q, edge2), areaNormal) / area2;
    double t = dot(cross(edge1, q), areaNormal) / area2;
    if (!(s >= 0 && s <= 1 && t >= 0 && t <= 1)) return 0;
    return choice * (distance * distance / cosArea);
}

std::optional<LightLeSample> QuadLight::sampleLe(Point2 uPos, Point2 uDir,
                                                 const LightLeContext& ctx) const {
    const Vec3 areaNormal = cross(edge1, edge2);
    const double area = length(areaNormal);
    if (!(area > 0)) return std::nullopt;
    const Vec3 p = position + edge1 * uPos.x + edge2 * uPos.y;
    return fromSurface(p, areaNormal / area, 1 / area, color, true, uDir, ctx);
}

LightLePdf QuadLight::pdfLe(const Vec3& origin, const Vec3& n, const Vec3& dir,
                            const LightLeContext& ctx) const {
    const double area = length(cross(edge1, edge2));
    if (!(area > 0)) return {};
    return {1 / area, pdfFromSurface(origin, n, true, dir, ctx)};
}

std::optional<LightBounds> QuadLight::bounds() const {
    const Vec3 a = position + edge1, b = position + edge1 + edge2, c = position + edge2;
    const Vec3 lo = min(min(position, a), min(b, c)), hi = max(max(position, a), max(b, c));
    const Vec3 areaNormal = cross(edge1, edge2);
    const double phi = kPi * length(areaNormal) * brightness(color);
    if (!(phi > 0)) return std::nullopt;
    return LightBounds::surface(lo, hi, phi, areaNormal, false);
}

std::ostream& operator<<(std::ostream& out, const QuadLight& l) {
    return out << "QuadLight{corner " << l.position << ", edges " << l.edge1 << " and " << l.edge2
               << ", radiance " << l.color << "}";
}

}  // namespace glint
