#include "glint/render/media.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "glint/math/sampling.h"

namespace glint {
namespace {

double mean(const Vec3& v) { return (v.x + v.y + v.z) / 3; }

/// The part [t0, t1] of `ray` over [0, tEnd) where `m` may have any density: all of it when
/// homogeneous, else where the ray crosses the grid's box (an affine map keeps ray parameters).
bool extent(const Medium& m, const Ray& ray, double tEnd, double& t0, double& t1) {
    t0 = 0;
    t1 = tEnd;
    if (m.homogeneous()) return true;
    const DensityGrid& g = *m.grid;
    const Vec3 o = m.worldFromIndex.inversePoint(ray.origin);
    const Vec3 d = m.worldFromIndex.inverseVector(ray.dir);
    const double hi[3] = {static_cast<double>(g.nx), static_cast<double>(g.ny),
                          static_cast<double>(g.nz)};
    for (int a = 0; a < 3; ++a) {
        if (d[a] == 0) {
            if (!(o[a] >= 0 && o[a] <= hi[a])) return false;
            continue;
        }
        double ta = (0 - o[a]) / d[a], tb = (hi[a] - o[a]) / d[a];
        if (ta > tb) std::swap(ta, tb);
        t0 = std::max(t0, ta);
        t1 = std::min(t1, tb);
    }
    return t0 < t1;
}

/// The distance to the next tentative collision at rate `rate` per unit of ray parameter.
double nextCollision(double rate, Rng& rng) { return -std::log(1 - rng.uniform()) / rate; }

}  // namespace

double HenyeyGreenstein::eval(const Vec3& wo, const Vec3& wi) const {
    const double c = -dot(wo, wi);  // between the travel direction -wo and wi
    const double denom = 1 + g * g - 2 * g * c;
    return (1 - g * g) / (4 * std::numbers::pi * denom * std::sqrt(denom));
}

Vec3 HenyeyGreenstein::sample(const Vec3& wo, Point2 u) const {
    double c;
    if (std::abs(g) < 1e-3) {
        c = 1 - 2 * u.x;
    } else {
        const double s = (1 - g * g) / (1 - g + 2 * g * u.x);
        c = std::clamp((1 + g * g - s * s) / (2 * g), -1.0, 1.0);
    }
    const double sn = std::sqrt(std::max(0.0, 1 - c * c));
    const double phi = 2 * std::numbers::pi * u.y;
    const Frame frame(-wo);
    return normalize(frame.toWorld(Vec3(sn * std::cos(phi), sn * std::sin(phi), c)));
}

MediumEvent sampleMedium(const Medium& m, const Ray& ray, double tEnd, Rng& rng, Vec3& beta) {
    const Vec3 sigmaT = m.sigmaT();
    const double majorant = maxComponent(sigmaT) * m.densityBound;  // per unit length
    double t0, t1;
    if (!(majorant > 0) || !extent(m, ray, tEnd, t0, t1)) return {};
    const double rate = majorant * length(ray.dir);  // per unit of ray parameter
    for (double t = t0;;) {
        t += nextCollision(rate, rng);
        if (!(t < t1)) return {};
        const double d = m.homogeneous() ? 1.0 : m.density(ray.origin + ray.dir * t);
        const Vec3 sa = m.sigmaA * d, ss = m.sigmaS * d;
        const Vec3 sn = max(Vec3(majorant) - sa - ss, Vec3(0));
        const double ps = mean(ss) / majorant, pn = mean(sn) / majorant;
        const double u = rng.uniform();
        if (u < ps) {
            beta = beta * ss / (majorant * ps);
            return {MediumEvent::Kind::Scattered, t};
        }
        if (u < ps + pn) {
            beta = beta * sn / (majorant * pn);
            continue;
        }
        return {MediumEvent::Kind::Absorbed, t};
    }
}

Vec3 mediumTransmittance(const Medium& m, const Ray& ray, double tEnd, Rng& rng) {
    const Vec3 sigmaT = m.sigmaT();
    if (sigmaT == Vec3(0)) return Vec3(1);
    double t0, t1;
    if (!extent(m, ray, tEnd, t0, t1)) return Vec3(1);
    const double len = length(ray.dir);
    if (m.homogeneous()) {
        if (!std::isfinite(t1)) return Vec3(0);
        const double d = (t1 - t0) * len;
        return {std::exp(-sigmaT.x * d), std::exp(-sigmaT.y * d), std::exp(-sigmaT.z * d)};
    }
    const double majorant = maxComponent(sigmaT) * m.densityBound;
    if (!(majorant > 0)) return Vec3(1);
    Vec3 tr(1);
    for (double t = t0;;) {
        t += nextCollision(majorant * len, rng);
        if (!(t < t1)) return tr;
        const double d = m.density(ray.origin + ray.dir * t);
        tr = tr * max(Vec3(1) - sigmaT * (d / majorant), Vec3(0));
        // Russian roulette once little is left: unbiased, and bounded work.
        const double most = maxComponent(tr);
        if (most < 0.05) {
            if (rng.uniform() >= 0.5) return Vec3(0);
            tr = tr * 2.0;
        }
    }
}

}  // namespace glint
