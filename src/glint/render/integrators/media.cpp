#include "glint/render/integrators/media.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "glint/math/sampling.h"

namespace glint {
namespace {

double mean(const Vec3& v) { return (v.x + v.y + v.z) / 3; }

/// A ray in a grid's index space, where it keeps its parameter (the map is affine): placed once
/// per tracking call, so that each collision looks the density up without a transform.
struct IndexRay {
    Vec3 o, d;
    IndexRay(const Medium& m, const Ray& ray) {
        if (m.homogeneous()) return;
        o = m.worldFromIndex.inversePoint(ray.origin);
        d = m.worldFromIndex.inverseVector(ray.dir);
    }
    /// The medium's density at parameter t (1 when homogeneous).
    double density(const Medium& m, double t) const {
        return m.homogeneous() ? 1.0 : m.grid->lookup(o + d * t);
    }
};

/// The part [t0, t1] of the ray over [0, tEnd) where `m` may have any density: all of it when
/// homogeneous, else where the ray (`r`, in index space) crosses the grid's box.
bool extent(const Medium& m, const IndexRay& r, double tEnd, double& t0, double& t1) {
    t0 = 0;
    t1 = tEnd;
    if (m.homogeneous()) return true;
    const DensityGrid& g = *m.grid;
    const Vec3 &o = r.o, &d = r.d;
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

/// Calls visit(ta, tb, bound) for the consecutive pieces [ta, tb) of [t0, t1) along `ray`, each
/// with a bound on the medium's density over it, until visit returns false: one piece for a
/// homogeneous medium or a grid without majorants, else one per block of the majorant grid the
/// ray crosses (a 3-D DDA, Amanatides and Woo 1987, in the grid's index space, where the ray
/// keeps its parameter).
template <typename Visit>
void forEachMajorant(const Medium& m, const IndexRay& r, double t0, double t1, Visit visit) {
    if (m.homogeneous() || !m.majorants) {
        visit(t0, t1, m.densityBound);
        return;
    }
    const MajorantGrid& g = *m.majorants;
    constexpr double B = MajorantGrid::kBlock;
    const Vec3 &o = r.o, &d = r.d;
    const Vec3 start = o + d * t0;
    const int n[3] = {g.nx, g.ny, g.nz};
    int cell[3], step[3];
    double next[3], delta[3];
    for (int a = 0; a < 3; ++a) {
        cell[a] = std::clamp(static_cast<int>(std::floor(start[a] / B)), 0, n[a] - 1);
        if (d[a] > 0) {
            step[a] = 1;
            next[a] = ((cell[a] + 1) * B - o[a]) / d[a];
            delta[a] = B / d[a];
        } else if (d[a] < 0) {
            step[a] = -1;
            next[a] = (cell[a] * B - o[a]) / d[a];
            delta[a] = -B / d[a];
        } else {
            step[a] = 0;
            next[a] = delta[a] = std::numeric_limits<double>::infinity();
        }
    }
    for (double t = t0; t < t1;) {
        const int a = next[0] < next[1] ? (next[0] < next[2] ? 0 : 2) : (next[1] < next[2] ? 1 : 2);
        const double tb = std::min(std::max(next[a], t), t1);
        if (!visit(t, tb, static_cast<double>(g.at(cell[0], cell[1], cell[2])))) return;
        t = tb;
        cell[a] += step[a];
        if (cell[a] < 0 || cell[a] >= n[a]) return;
        next[a] += delta[a];
    }
}

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
    const double sigmaMax = maxComponent(m.sigmaT());  // per unit length, at density 1
    const IndexRay r(m, ray);
    double t0, t1;
    if (!(sigmaMax * m.densityBound > 0) || !extent(m, r, tEnd, t0, t1)) return {};
    const double len = length(ray.dir);
    MediumEvent event;
    forEachMajorant(m, r, t0, t1, [&](double ta, double tb, double bound) {
        const double majorant = sigmaMax * bound;  // per unit length, over [ta, tb)
        if (!(majorant > 0)) return true;          // nothing here to collide with
        for (double t = ta;;) {
            t += nextCollision(majorant * len, rng);
            if (!(t < tb)) return true;  // on into the next piece: collisions are memoryless
            const double d = r.density(m, t);
            const Vec3 sa = m.sigmaA * d, ss = m.sigmaS * d;
            const Vec3 sn = max(Vec3(majorant) - sa - ss, Vec3(0));
            const double ps = mean(ss) / majorant, pn = mean(sn) / majorant;
            const double u = rng.uniform();
            if (u < ps) {
                beta = beta * ss / (majorant * ps);
                event = {MediumEvent::Kind::Scattered, t};
                return false;
            }
            if (u < ps + pn) {
                beta = beta * sn / (majorant * pn);
                continue;
            }
            event = {MediumEvent::Kind::Absorbed, t};
            return false;
        }
    });
    return event;
}

Vec3 mediumTransmittance(const Medium& m, const Ray& ray, double tEnd, Rng& rng) {
    const Vec3 sigmaT = m.sigmaT();
    if (sigmaT == Vec3(0)) return Vec3(1);
    const IndexRay r(m, ray);
    double t0, t1;
    if (!extent(m, r, tEnd, t0, t1)) return Vec3(1);
    const double len = length(ray.dir);
    if (m.homogeneous()) {
        if (!std::isfinite(t1)) return Vec3(0);
        const double d = (t1 - t0) * len;
        return {std::exp(-sigmaT.x * d), std::exp(-sigmaT.y * d), std::exp(-sigmaT.z * d)};
    }
    const double sigmaMax = maxComponent(sigmaT);
    Vec3 tr(1);
    forEachMajorant(m, r, t0, t1, [&](double ta, double tb, double bound) {
        const double majorant = sigmaMax * bound;
        if (!(majorant > 0)) return true;
        for (double t = ta;;) {
            t += nextCollision(majorant * len, rng);
            if (!(t < tb)) return true;
            const double d = r.density(m, t);
            tr = tr * max(Vec3(1) - sigmaT * (d / majorant), Vec3(0));
            // Russian roulette once little is left: unbiased, and bounded work.
            if (maxComponent(tr) < 0.05) {
                if (rng.uniform() >= 0.5) {
                    tr = Vec3(0);
                    return false;
                }
                tr = tr * 2.0;
            }
        }
    });
    return tr;
}

}  // namespace glint
