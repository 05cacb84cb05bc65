#include "glint/render/shadow_catcher.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "glint/core/spawn.h"
#include "glint/scene/light.h"

namespace glint {
namespace {

constexpr double kPi = std::numbers::pi;

/// Lights beyond this many cast their shadows through one of them chosen at random.
constexpr size_t kLightsEach = 8;

/// `a / b` per channel, 0 where b is 0.
Vec3 ratio(const Vec3& a, const Vec3& b) {
    auto div = [](double x, double y) { return y > 0 ? x / y : 0.0; };
    return {div(a.x, b.x), div(a.y, b.y), div(a.z, b.z)};
}

}  // namespace

Vec3 upwardIrradiance(const Scene& scene) {
    if (!scene.environment) {
        // The gradient down (1 - t) + up t, t = (y + 1) / 2, over the upper hemisphere:
        // the integrals of (1 - t) cos and of t cos are pi / 6 and 5 pi / 6.
        return scene.background.down * (kPi / 6) + scene.background.up * (5 * kPi / 6);
    }
    // Each texel (as stored, times the scale) weighted by the integral of cos(theta) over its
    // cell of the upper hemisphere, (2 pi / w) (sin^2 theta1 - sin^2 theta0) / 2: exact for a
    // map constant across each row's cells; the bilinear lookup between rows moves weight by
    // a fraction of a texel. Rotation about +y changes nothing.
    const EnvironmentMap& map = *scene.environment;
    const int w = map.width(), h = map.height();
    Vec3 sum(0);
    for (int y = 0; 2 * y < h; ++y) {
        double t0 = kPi * y / h, t1 = std::min(kPi * (y + 1) / h, kPi / 2);
        double s0 = std::sin(t0), s1 = std::sin(t1);
        Vec3 row(0);
        for (int x = 0; x < w; ++x) row += map.texel(x, y);
        sum += row * (0.5 * (s1 * s1 - s0 * s0) * 2 * kPi / w);
    }
    return sum * map.scale();
}

ShadowCatcherShading::ShadowCatcherShading(const Scene& scene)
    : scene_(scene),
      height_(scene.shadowCatcher ? scene.shadowCatcher->height : 0),
      environmentIrradiance_(upwardIrradiance(scene)) {}

std::optional<double> ShadowCatcherShading::intersect(const Ray& ray) const {
    if (!(ray.dir.y < 0) || !(ray.origin.y > height_)) return std::nullopt;
    double t = (height_ - ray.origin.y) / ray.dir.y;
    if (!(t > ray.tMin && t < ray.tMax)) return std::nullopt;
    return t;
}

Vec3 ShadowCatcherShading::radiance(const Vec3& p, const Vec3& dir, Point2 uEnvironment,
                                    double uLight, RayCounts& counts) const {
    const Vec3 behind = scene_.backgroundRadiance(dir);
    if (behind == Vec3(0)) return behind;
    const double offset = scene_.spawnOffset();
    Vec3 irradiance = environmentIrradiance_, blocked(0);

    // The environment: one direction, drawn as the light sampler draws it.
    std::optional<Vec3> wi;
    Vec3 L;
    double pdf = 0;
    if (scene_.environment) {
        if (auto s = scene_.environment->sample(uEnvironment)) {
            wi = s->wi;
            L = s->L;
            pdf = s->pdf;
        }
    } else {
        Vec3 d = sampleCosineHemisphere(uEnvironment);  // about +z: turned to +y
        wi = Vec3(d.x, d.z, -d.y);
        L = scene_.background.eval(*wi);
        pdf = wi->y / kPi;
    }
    if (wi && wi->y > 0 && pdf > 0 && !(L == Vec3(0))) {
        counts.shadow++;
        if (scene_.bvh().occluded(spawnRay(p, *wi, offset))) blocked += L * (wi->y / pdf);
    }

    // The lights: each one's irradiance, and its shadow ray (or, among many lights, one
    // shadow ray to a light chosen at random, counted for all).
    const auto& lights = scene_.lights;
    const bool each = lights.size() <= kLightsEach;
    const size_t chosen =
        each ? 0
             : std::min(static_cast<size_t>(uLight * static_cast<double>(lights.size())),
                        lights.size() - 1);
    for (size_t i = 0; i < lights.size(); ++i) {
        std::optional<LightLiSample> s = lights[i].sampleLi(p, uEnvironment);
        if (!s || !(s->wi.y > 0)) continue;
        Vec3 e = s->L * (s->wi.y * s->invPdf);
        irradiance += e;
        if (!each && i != chosen) continue;
        double end = s->distance;
        if (std::isfinite(end)) end -= spawnOffset(p + s->wi * end, offset);
        counts.shadow++;
        if (scene_.bvh().occluded(spawnRay(p, s->wi, offset, end)))
            blocked += each ? e : e * static_cast<double>(lights.size());
    }
    return behind * (Vec3(1) - ratio(blocked, irradiance));
}

}  // namespace glint
