#include "glint/render/light_sampler.h"

#include <cmath>
#include <numbers>

#include "glint/geometry/surface_sampling.h"

namespace glint {
namespace {

constexpr double kPi = std::numbers::pi;

/// Brightness of a colour for weighing lights: its luminance (Rec. 709), or its largest
/// channel if that is not positive (a colour of negative channels).
double brightness(const Vec3& c) {
    double y = luminance(c);
    return y > 0 ? y : std::max(maxComponent(c), 0.0);
}

}  // namespace

LightSampler::LightSampler(const Scene& scene) : scene_(scene) {
    const Primitives& prims = scene.primitives;
    Bounds3f b = prims.bounds();
    if (!b.empty()) sceneRadius_ = std::max(length(Vec3(b.hi) - Vec3(b.lo)) / 2, 1e-6);
    std::vector<LightBounds> bounded;
    auto addBounded = [&](const Entry& e, const LightBounds& lb) {
        lightOfTreeLeaf_.push_back(static_cast<uint32_t>(lights_.size()));
        lights_.push_back(e);
        bounded.push_back(lb);
    };
    auto addInfinite = [&](const Entry& e) {
        infinite_.push_back(static_cast<uint32_t>(lights_.size()));
        lights_.push_back(e);
    };

    // Delta lights. A point light's power is estimated at unit distance; quad lights are
    // represented by their emissive triangles below.
    for (uint32_t i = 0; i < scene.lights.size(); ++i) {
        const Light& l = scene.lights[i];
        if (l.kind == Light::Kind::Point) {
            double att = std::max(l.attenuation.x + l.attenuation.y + l.attenuation.z, 1e-6);
            const double power = 4 * kPi * brightness(l.color) / att;
            if (power > 0) addBounded({Kind::Point, i}, LightBounds::point(l.position, power));
        } else if (l.kind == Light::Kind::Directional) {
            if (brightness(l.color) > 0) addInfinite({Kind::Directional, i});
        }
    }

    // Emissive surfaces: power pi A Le (one side; both sides emit unless front-only).
    auto emits = [&](uint32_t id) {
        uint32_t m = prims.materialOf(id);
        return m != Primitives::kMixedMaterials && brightness(scene.materials[m].emission) > 0;
    };
    const uint32_t boundedCount = prims.boundedCount();
    for (uint32_t id = 0; id < boundedCount; ++id) {
        if (prims.isInstance(id) || !emits(id)) continue;
        if (lightOfPrimitive_.empty()) lightOfPrimitive_.assign(boundedCount, UINT32_MAX);
        const Material& m = scene.materials[prims.materialOf(id)];
        Entry e{Kind::Triangle, id, m.frontEmissionOnly};
        e.emission = m.emission;
        if (m.pbr != 0 && scene.pbr(m.pbr).emissiveTexture && id < prims.triangleCount())
            e.texturedPbr = m.pbr;
        double area;
        Vec3 lo, hi, normal(0);
        if (id < prims.triangleCount()) {
            auto v = prims.triangleVertices(id);
            const Vec3 va(v[0]), vb(v[1]), vc(v[2]);
            Vec3 cr = cross(vb - va, vc - va);
            area = 0.5 * length(cr);
            if (!(area > 0)) continue;
            e.pdfArea = 1 / area;
            e.c = vc;
            e.ca = va - vc;
            e.cb = vb - vc;
            e.n = cr / (2 * area);
            lo = min(va, min(vb, vc));
            hi = max(va, max(vb, vc));
            normal = e.n;
        } else {
            const Bounds3f box = prims.bounds(id);
            lo = Vec3(box.lo);
            hi = Vec3(box.hi);
            if (prims.isSphere(id)) {
                e.kind = Kind::Sphere;
                area = approximateArea(prims.sphere(id - prims.triangleCount()));
            } else {
                e.kind = Kind::Shape;
                area = approximateArea(
                    prims.shape(id - prims.triangleCount() - prims.sphereCount()));
            }
        }
        const double power = kPi * area * brightness(m.emission) * (e.frontOnly ? 1 : 2);
        if (!(power > 0)) continue;
        lightOfPrimitive_[id] = static_cast<uint32_t>(lights_.size());
        // A sphere or shape emits about every normal; a triangle about its own, from both
        // sides unless front-only.
        addBounded(e, LightBounds::surface(lo, hi, power, normal, !e.frontOnly));
    }

    // The environment map, or the background if it is not black.
    double env = scene.environment
                     ? scene.environment->power(sceneRadius_)
                     : brightness((scene.background.down + scene.background.up) * 0.5);
    if (env > 0) {
        environment_ = static_cast<uint32_t>(lights_.size());
        addInfinite({Kind::Environment, 0});
    }

    tree_ = LightTree(bounded);
    treeLeafOf_.assign(lights_.size(), UINT32_MAX);
    for (uint32_t k = 0; k < lightOfTreeLeaf_.size(); ++k) treeLeafOf_[lightOfTreeLeaf_[k]] = k;
    const double nInfinite = static_cast<double>(infinite_.size());
    pInfinite_ = nInfinite / (nInfinite + (tree_.empty() ? 0 : 1));
}

std::optional<LightSample> LightSampler::sample(const Vec3& p, const Vec3& n, double uLight,
                                                Point2 u) const {
    if (lights_.empty()) return std::nullopt;
    uint32_t index;
    double choice;
    if (uLight < pInfinite_) {
        const size_t count = infinite_.size();
        index = infinite_[std::min(static_cast<size_t>(uLight / pInfinite_ * count), count - 1)];
        choice = pInfinite_ / static_cast<double>(count);
    } else {
        const double v = std::min((uLight - pInfinite_) / (1 - pInfinite_), 0x1.fffffffffffffp-1);
        std::optional<LightTree::Choice> c = tree_.sample(p, n, v);
        if (!c) return std::nullopt;
        index = lightOfTreeLeaf_[c->light];
        choice = (1 - pInfinite_) * c->probability;
    }
    std::optional<LightSample> s = sampleEntry(lights_[index], p, u);
    if (s) s->pdf *= choice;
    return s;
}

double LightSampler::choiceProbability(size_t index, const Vec3& p, const Vec3& n) const {
    if (index >= lights_.size()) return 0;
    const uint32_t leaf = treeLeafOf_[index];
    if (leaf == UINT32_MAX) return pInfinite_ / static_cast<double>(infinite_.size());
    return (1 - pInfinite_) * tree_.pmf(p, n, leaf);
}

std::optional<LightSample> LightSampler::sampleEntry(const Entry& e, const Vec3& p,
                                                     Point2 u) const {
    const Primitives& prims = scene_.primitives;
    switch (e.kind) {
        case Kind::Point:
        case Kind::Directional: {
            std::optional<LightLiSample> ls = scene_.lights[e.index].sampleLi(p, u);
            if (!ls) return std::nullopt;
            return LightSample{ls->wi, ls->L, 1, ls->distance, true};
        }
        case Kind::Environment: {
            if (scene_.environment) {
                std::optional<EnvironmentMap::Sample> s = scene_.environment->sample(u);
                if (!s || !(s->pdf > 0)) return std::nullopt;
                return LightSample{s->wi, s->L, s->pdf, kInfinity, false};
            }
            Vec3 wi = sampleUniformSphere(u);
            return LightSample{wi, environment(wi), 1 / (4 * kPi), kInfinity, false};
        }
        default:
            break;
    }
    SurfaceSample ss;
    Vec3 emission = e.emission;
    if (e.kind == Kind::Triangle) {
        auto [b0, b1] = sampleUniformTriangle(u);  // as sampleTriangle, from stored edges
        ss = {e.c + e.ca * b0 + e.cb * b1, e.n, e.pdfArea};
        if (e.texturedPbr != 0)  // the point is a b0 + b b1 + c (1 - b0 - b1)
            emission = emissionAt(scene_.pbr(e.texturedPbr),
                                  prims.triangleAttributes(e.index, b1, 1 - b0 - b1));
    } else if (e.kind == Kind::Sphere) {
        ss = sampleSphere(prims.sphere(e.index - prims.triangleCount()), u);
    } else {
        ss = sampleShape(prims.shape(e.index - prims.triangleCount() - prims.sphereCount()), u);
    }
    Vec3 d = ss.p - p;
    double d2 = dot(d, d);
    if (!(d2 > 0)) return std::nullopt;
    double dist = std::sqrt(d2);
    Vec3 wi = d / dist;
    double cosLight = dot(wi, ss.n);  // < 0: the sample faces p
    if (e.frontOnly ? !(cosLight < 0) : cosLight == 0) return std::nullopt;
    double pdf = ss.pdfArea * d2 / std::abs(cosLight);
    if (!(pdf > 0) || !std::isfinite(pdf)) return std::nullopt;
    return LightSample{wi, emission, pdf, dist, false};
}

double LightSampler::pdfHit(const Vec3& from, const Vec3& fromN, const Hit& hit,
                            const SurfaceInteraction& si) const {
    if (lightOfPrimitive_.empty() || hit.primId >= lightOfPrimitive_.size()) return 0;
    uint32_t index = lightOfPrimitive_[hit.primId];
    if (index == UINT32_MAX) return 0;
    const Entry& e = lights_[index];
    const Primitives& prims = scene_.primitives;
    double pdfArea = e.pdfArea;
    if (e.kind == Kind::Sphere)
        pdfArea = spherePdfArea(prims.sphere(e.index - prims.triangleCount()), si.ng);
    else if (e.kind == Kind::Shape)
        pdfArea =
            shapePdfArea(prims.shape(e.index - prims.triangleCount() - prims.sphereCount()), si.ng);
    Vec3 d = si.p - from;
    double d2 = dot(d, d);
    double cosLight = std::abs(dot(d, si.ng)) / std::sqrt(d2);
    if (!(cosLight > 0)) return 0;
    return choiceProbability(index, from, fromN) * pdfArea * d2 / cosLight;
}

Vec3 LightSampler::environment(const Vec3& dir, double* pdf) const {
    if (!scene_.environment) {
        *pdf = pdfEnvironment(dir);
        return scene_.background.eval(dir);
    }
    const EnvironmentMap& map = *scene_.environment;
    const Point2 st = map.imageCoordinates(dir);
    *pdf = environment_ == UINT32_MAX ? 0 : choiceProbability(environment_, {}, {}) * map.pdfAt(st);
    return map.evalAt(st);
}

double LightSampler::pdfEnvironment(const Vec3& dir) const {
    if (environment_ == UINT32_MAX) return 0;
    double pdf = scene_.environment ? scene_.environment->pdf(dir) : 1 / (4 * kPi);
    return choiceProbability(environment_, {}, {}) * pdf;
}

}  // namespace glint
