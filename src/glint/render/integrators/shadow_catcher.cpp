#include "glint/render/integrators/shadow_catcher.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "glint/core/spawn.h"
#include "glint/scene/light_spec.h"

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

namespace {

/// Of row y of a map h rows high: the part of its height, in rows, above the horizon (1, or
/// 1/2 for the middle row of an odd height).
double rowAbove(int y, int h) { return std::min(1.0, 0.5 * h - y); }

}  // namespace

ShadowCatcherShading::ShadowCatcherShading(const Scene& scene)
    : scene_(scene),
      height_(scene.shadowCatcher ? scene.shadowCatcher->height : 0),
      environmentIrradiance_(upwardIrradiance(scene)) {
    for (const LightSpec& l : scene.lights) lights_.push_back(lightFromSpec(l));
    emitters_ = std::any_of(scene.materials.begin(), scene.materials.end(),
                            [](const Material& m) { return !(m.emission == Vec3(0)); });
    if (!scene.environment) return;
    const EnvironmentMap& map = *scene.environment;
    const int w = map.width(), h = map.height();
    upperRows_ = (h + 1) / 2;
    auto lum = [&](int x, int y) {
        return luminance(map.texel((x + w) % w, std::clamp(y, 0, h - 1)));
    };
    upper_ = Distribution2D(static_cast<size_t>(w), static_cast<size_t>(upperRows_), [&](size_t r) {
        const int y = static_cast<int>(r);
        double t0 = kPi * y / h, t1 = kPi * (y + rowAbove(y, h)) / h;
        double s0 = std::sin(t0), s1 = std::sin(t1);
        double cosIntegral = 0.5 * (s1 * s1 - s0 * s0) * 2 * kPi / w;
        std::vector<double> weights(static_cast<size_t>(w));
        // The mean of the bilinear lookup over the texel's cell: [1/8, 3/4, 1/8] of the texel
        // and its neighbours on each axis (as EnvironmentMap weighs its cells), so that a cell
        // has weight wherever eval() can return radiance in it.
        constexpr double k[3] = {0.125, 0.75, 0.125};
        for (int x = 0; x < w; ++x) {
            double mean = 0;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx)
                    mean += k[dy + 1] * k[dx + 1] * lum(x + dx, y + dy);
            weights[static_cast<size_t>(x)] = mean * cosIntegral;
        }
        return weights;
    });
}

std::optional<ShadowCatcherShading::EnvironmentSample> ShadowCatcherShading::sampleEnvironment(
    Point2 u) const {
    if (!scene_.environment) {
        // The background: by cos(theta) over the upper hemisphere (about +z, turned to +y).
        Vec3 d = sampleCosineHemisphere(u);
        Vec3 wi(d.x, d.z, -d.y);
        if (!(wi.y > 0)) return std::nullopt;
        return EnvironmentSample{wi, scene_.background.eval(wi), wi.y / kPi};
    }
    const EnvironmentMap& map = *scene_.environment;
    double density = 0;
    size_t column = 0, row = 0;
    Point2 st = upper_.sample(u, &density, &column, &row);
    if (!(density > 0)) return std::nullopt;
    // Uniform in (s, t) across the cell: t runs over the row's part above the horizon.
    const int y = static_cast<int>(row), h = map.height();
    const double part = rowAbove(y, h);
    const double f = std::clamp(st.y * upperRows_ - y, 0.0, 1.0);
    const double t = (y + f * part) / h;
    Vec3 wi = map.direction({st.x, t});
    double sinTheta = std::sin(kPi * t);
    // d omega = sin(theta) d theta d phi = sin(theta) (pi part upperRows / h) (2 pi) d(unit
    // square): the density over the unit square becomes one over solid angle.
    double pdf = density / (2 * kPi * kPi * sinTheta * part * upperRows_ / h);
    if (!(wi.y > 0) || !(pdf > 0) || !std::isfinite(pdf)) return std::nullopt;
    return EnvironmentSample{wi, map.evalAt({st.x, t}), pdf};
}

std::optional<double> ShadowCatcherShading::intersect(const Ray& ray) const {
    if (!(ray.dir.y < 0) || !(ray.origin.y > height_)) return std::nullopt;
    double t = (height_ - ray.origin.y) / ray.dir.y;
    if (!(t > ray.tMin && t < ray.tMax)) return std::nullopt;
    return t;
}

ShadowCatcherShading::Blocker ShadowCatcherShading::blocker(const Ray& shadow) const {
    if (!emitters_) return scene_.occluded(shadow) ? Blocker::Surface : Blocker::None;
    Hit hit;  // what blocks it, to tell an emitter: one search either way
    if (!scene_.intersect(shadow, hit)) return Blocker::None;
    const SurfaceInteraction si = scene_.primitives.interaction(shadow, hit);
    return scene_.materials[si.material].emission == Vec3(0) ? Blocker::Surface : Blocker::Emitter;
}

Vec3 ShadowCatcherShading::radiance(const Vec3& p, const Vec3& dir, Point2 uEnvironment,
                                    double uLight, RayCounts& counts) const {
    const Vec3 behind = scene_.backgroundRadiance(dir);
    if (behind == Vec3(0)) return behind;
    const double offset = scene_.spawnOffset();
    Vec3 irradiance = environmentIrradiance_, blocked(0);

    // The environment: one direction over the upper hemisphere.
    if (std::optional<EnvironmentSample> s = sampleEnvironment(uEnvironment);
        s && !(s->L == Vec3(0))) {
        counts.shadow++;
        if (scene_.occluded(spawnRay(p, s->wi, offset))) blocked += s->L * (s->wi.y / s->pdf);
    }

    // The lights: each one's irradiance, and its shadow ray (or, among many lights, one
    // shadow ray to a light chosen at random, counted for all).
    const std::vector<Light>& lights = lights_;
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
        const Blocker b = blocker(spawnRay(p, s->wi, offset, end));
        if (b == Blocker::None) continue;
        // A light inside an emitting surface (a bulb around a point light, as glTF files
        // have them) lights the scene through its bulb alone: it neither weighs in E nor
        // shadows the plane, where it would darken a wide halo around the bulb.
        if (b == Blocker::Emitter) {
            if (each) irradiance -= e;
            continue;
        }
        blocked += each ? e : e * static_cast<double>(lights.size());
    }
    return behind * (Vec3(1) - ratio(blocked, irradiance));
}

}  // namespace glint
