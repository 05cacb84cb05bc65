#include "glint/render/lights/plane_light.h"

#include <cmath>
#include <ostream>

#include "glint/render/lights/light_util.h"

namespace glint {

using namespace light_util;

std::optional<LightLiSample> PlaneLight::sampleLi(const Vec3& p, Point2 u) const {
    // Cosine-weighted about the normal, over the directions that meet the plane.
    const double side = dot(p - point, normal);
    if (side == 0 || (frontOnly && side < 0)) return std::nullopt;
    const Frame frame(side > 0 ? -normal : normal);
    const Vec3 local = sampleCosineHemisphere(u);
    if (!(local.z > 0)) return std::nullopt;
    const Vec3 wi = normalize(frame.toWorld(local));
    const double pdf = local.z / kPi;
    return LightLiSample{wi, emission, pdf, 1 / pdf, std::abs(side) / local.z, false};
}

double PlaneLight::pdfLi(const Vec3& from, const LightPoint& at, double choice) const {
    const double side = dot(from - point, normal);
    if (side == 0 || (frontOnly && side < 0)) return 0;
    const double cosPlane = std::abs(dot(normalize(at.p - from), normal));
    return choice * cosPlane / kPi;
}

std::optional<LightLeSample> PlaneLight::sampleLe(Point2 uPos, Point2 uDir,
                                                  const LightLeContext& ctx) const {
    // Light arrives at the target from the plane's side of it, the same from every direction
    // of that half of the sphere: uniformly over it, across the target's disc, from where the
    // ray leaves the plane.
    const double side = dot(ctx.center - point, normal);
    if (side == 0 || (frontOnly && side < 0)) return std::nullopt;
    const Vec3 towardsPlane = side > 0 ? -normal : normal;
    const Vec3 local = sampleUniformHemisphere(uDir);
    const Vec3 towards = normalize(Frame(towardsPlane).toWorld(local));
    LightLeSample s = acrossDisc(towards, emission, 1 / (2 * kPi), uPos, ctx);
    // The ray through the disc's point, from the plane; none where that point is behind it.
    const Vec3 onDisc = s.ray.origin + s.ray.dir * ctx.far;
    const double height = dot(onDisc - point, normal);
    const double cosine = dot(s.ray.dir, normal);
    if (!(height * side > 0) || !(cosine * side > 0)) return std::nullopt;
    s.n = side > 0 ? normal : -normal;
    s.p = onDisc - s.ray.dir * (height / cosine);
    s.ray = spawnRayOffSurface(s.p, s.n, s.ray.dir, ctx.offset);
    // The disc's density over the plane's area, which the disc's points fill stretched by
    // 1 / cos: beta (the disc's) is then L cos / (pdfPos pdfDir), as for any surface.
    s.pdfPos *= std::abs(cosine);
    return s;
}

LightLePdf PlaneLight::pdfLe(const Vec3&, const Vec3&, const Vec3& dir,
                             const LightLeContext& ctx) const {
    const double side = dot(ctx.center - point, normal);
    const double cosine = dot(dir, normal);
    if (side == 0 || (frontOnly && side < 0) || !(cosine * side > 0)) return {};
    return {std::abs(cosine) / (kPi * ctx.radius * ctx.radius), 1 / (2 * kPi)};
}

double PlaneLight::infiniteImportance() const { return kPi * kPi * brightness(emission); }

std::ostream& operator<<(std::ostream& out, const PlaneLight& l) {
    out << "PlaneLight{through " << l.point << ", normal " << l.normal << ", emission "
        << l.emission;
    if (l.frontOnly) out << ", front only";
    return out << "}";
}

}  // namespace glint
