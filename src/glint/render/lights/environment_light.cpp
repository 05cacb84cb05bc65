#include "glint/render/lights/environment_light.h"

#include <cmath>
#include <ostream>

#include "glint/render/lights/light_util.h"

namespace glint {

using namespace light_util;

EnvironmentLight EnvironmentLight::make(const EnvironmentMap* map, const Background& background) {
    EnvironmentLight l;
    l.map = map;
    l.background = background;
    // Its mean radiance L gives pi L from a hemisphere.
    const double meanRadiance =
        brightness(map ? map->averageRadiance() : (background.down + background.up) * 0.5);
    l.importance = kPi * kPi * meanRadiance;
    if (!map) return l;
    // Several times the mean: a sun's disc or a lamp's, not a bright sky.
    constexpr double kAboveMean = 4;
    l.passThreshold = kAboveMean * luminance(map->averageRadiance());
    double above = 0, all = 0;
    for (int y = 0; y < map->height(); ++y) {
        // Texels of a row subtend the same solid angle, in proportion to the sine there.
        const double sinTheta = std::sin(kPi * (y + 0.5) / map->height());
        for (int x = 0; x < map->width(); ++x) {
            const double lum = luminance(map->texel(x, y) * map->scale()) * sinTheta;
            all += lum;
            if (lum > l.passThreshold * sinTheta) above += lum;
        }
    }
    l.passShare = all > 0 ? above / all : 0;
    return l;
}

Vec3 EnvironmentLight::radiance(const Vec3& dir, double* pdf, double choice) const {
    if (!map) {
        if (pdf) *pdf = choice * (1 / (4 * kPi));
        return background.eval(dir);
    }
    const Point2 st = map->imageCoordinates(dir);
    if (pdf) *pdf = choice * map->pdfAt(st);
    return map->evalAt(st);
}

std::optional<LightLiSample> EnvironmentLight::sampleLi(const Vec3&, Point2 u) const {
    if (map) {
        std::optional<EnvironmentMap::Sample> s = map->sample(u);
        if (!s || !(s->pdf > 0)) return std::nullopt;
        return LightLiSample{s->wi, s->L, s->pdf, 1 / s->pdf, kInfinity, false};
    }
    const Vec3 wi = sampleUniformSphere(u);
    return LightLiSample{wi, background.eval(wi), 1 / (4 * kPi), 4 * kPi, kInfinity, false};
}

double EnvironmentLight::pdfLi(const Vec3&, const LightPoint& at, double choice) const {
    return choice * (map ? map->pdf(at.wi) : 1 / (4 * kPi));
}

std::optional<LightLeSample> EnvironmentLight::sampleLe(Point2 uPos, Point2 uDir,
                                                        const LightLeContext& ctx) const {
    if (map) {
        std::optional<EnvironmentMap::Sample> s = map->sample(uDir);
        if (!s || !(s->pdf > 0)) return std::nullopt;
        return acrossDisc(s->wi, s->L, s->pdf, uPos, ctx);
    }
    const Vec3 wi = sampleUniformSphere(uDir);
    return acrossDisc(wi, background.eval(wi), 1 / (4 * kPi), uPos, ctx);
}

LightLePdf EnvironmentLight::pdfLe(const Vec3&, const Vec3&, const Vec3& dir,
                                   const LightLeContext& ctx) const {
    return {1 / (kPi * ctx.radius * ctx.radius), map ? map->pdf(-dir) : 1 / (4 * kPi)};
}

std::ostream& operator<<(std::ostream& out, const EnvironmentLight& l) {
    if (l.map)
        return out << "EnvironmentLight{map " << l.map->width() << "x" << l.map->height()
                   << ", mean radiance " << l.map->averageRadiance() << "}";
    return out << "EnvironmentLight{background " << l.background.down << " below, "
               << l.background.up << " above}";
}

}  // namespace glint
