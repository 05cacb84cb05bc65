#include "glint/render/lights/light_sampler.h"

#include <cmath>
#include <numbers>
#include <tuple>
#include <utility>

#include "glint/core/spawn.h"
#include "glint/geometry/surface_sampling.h"
#include "glint/math/sampling.h"
#include "glint/math/spherical_triangle.h"

namespace glint {
namespace {

constexpr double kPi = std::numbers::pi;

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

/// Whether a point at squared distance `d2` from the centre of a round sphere of `radius` is
/// outside it, clear of its surface: points on the surface (the inside of an emitting sphere
/// included, whose distance rounds either way) are sampled by area.
bool outsideSphere(double d2, double radius) {
    return radius > 0 && d2 > radius * radius * (1 + 1e-6);
}

/// sin^2 of the cone's half-angle below which its cosine is computed from the sine (pbrt-v4:
/// 1.5 degrees), where 1 - cos would lose its digits.
constexpr double kSmallCone = 0.00068523;

/// 1 - cos of the half-angle of the cone that a sphere of `radius` at squared distance `d2`
/// fills; its sine squared in `sin2Max`.
double oneMinusCosCone(double radius, double d2, double* sin2Max) {
    *sin2Max = radius * radius / d2;
    return *sin2Max < kSmallCone ? *sin2Max / 2 : 1 - std::sqrt(std::max(1 - *sin2Max, 0.0));
}

/// Brightness of a colour for weighing lights: its luminance (Rec. 709), or its largest
/// channel if that is not positive (a colour of negative channels).
double brightness(const Vec3& c) {
    double y = luminance(c);
    return y > 0 ? y : std::max(maxComponent(c), 0.0);
}

}  // namespace

LightSampler::LightSampler(const Scene& scene) : scene_(scene) {
    const Primitives& prims = scene.primitives;
    std::vector<LightBounds> bounded;
    auto addBounded = [&](Entry e, const LightBounds& lb) {
        lightOfTreeLeaf_.push_back(static_cast<uint32_t>(lights_.size()));
        e.power = lb.phi;
        e.middle = (lb.lo + lb.hi) * 0.5;
        lights_.push_back(e);
        bounded.push_back(lb);
    };
    // A light at infinity's weight is the irradiance it gives a surface facing it, times pi
    // as the light tree's importance has it (a Lambertian emitter of power phi gives pi times
    // the irradiance at normal incidence).
    auto addInfinite = [&](Entry e, double weight) {
        e.weight = weight;
        infinite_.push_back(static_cast<uint32_t>(lights_.size()));
        infiniteTotal_ += weight;
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
            if (brightness(l.color) > 0)
                addInfinite({Kind::Directional, i}, kPi * brightness(l.color));
        }
    }

    // Emissive surfaces: power pi A Le (one side; both sides emit unless front-only).
    auto emits = [&](uint32_t id) {
        uint32_t m = prims.materialOf(id);
        return m != Primitives::kMixedMaterials && brightness(scene.materials[m].emission) > 0;
    };
    const uint32_t boundedCount = prims.boundedCount();
    // A triangle's entry and bounds from its world corners; false if it has no area.
    auto triangleEntry = [&](Entry& e, const Vec3& va, const Vec3& vb, const Vec3& vc,
                             LightBounds& lb, double& area) {
        const Vec3 cr = cross(vb - va, vc - va);
        area = 0.5 * length(cr);
        if (!(area > 0)) return false;
        e.pdfArea = 1 / area;
        e.c = vc;
        e.ca = va - vc;
        e.cb = vb - vc;
        e.n = cr / (2 * area);
        lb.lo = min(va, min(vb, vc));
        lb.hi = max(va, max(vb, vc));
        return true;
    };
    // Its power: a textured emitter's is its own triangle's, the texture's mean over it
    // estimated at its centroid and halfway from there to each corner (an emissive map is
    // mostly black: most of a mesh's triangles emit nothing, and leave the tree). One whose
    // estimate is 0 is not sampled, which costs no bias: a ray that finds it counts its light
    // in full (pdfHit 0).
    auto power = [&](const Entry& e, const Material& m, double area) {
        double radiance = brightness(m.emission);
        if (e.texturedPbr != 0) {
            constexpr double kAt[4][2] = {
                {1.0 / 3, 1.0 / 3}, {2.0 / 3, 1.0 / 6}, {1.0 / 6, 2.0 / 3}, {1.0 / 6, 1.0 / 6}};
            double sum = 0;
            for (const auto& at : kAt) sum += brightness(texturedEmission(e, at[0], at[1]));
            radiance = sum / 4;
        }
        return kPi * area * radiance * (e.frontOnly ? 1 : 2);
    };
    for (uint32_t id = 0; id < boundedCount; ++id) {
        if (prims.isInstance(id)) {
            // Each emissive triangle of the placed mesh, placed.
            const Primitives& mesh = prims.sharedMesh(prims.instanceMesh(id));
            const Transform& t = prims.instanceTransform(id);
            for (uint32_t k = 0; k < mesh.triangleCount(); ++k) {
                const uint32_t mi = mesh.materialOf(k);
                if (mi == Primitives::kMixedMaterials ||
                    !(brightness(scene.materials[mi].emission) > 0))
                    continue;
                const Material& m = scene.materials[mi];
                Entry e{Kind::Triangle, id, m.frontEmissionOnly};
                e.sub = k;
                e.emission = m.emission;
                if (m.pbr != 0 && scene.pbr(m.pbr).emissiveTexture) e.texturedPbr = m.pbr;
                auto v = mesh.triangleVertices(k);
                LightBounds lb;
                double area;
                if (!triangleEntry(e, t.point(Vec3(v[0])), t.point(Vec3(v[1])), t.point(Vec3(v[2])),
                                   lb, area))
                    continue;
                const double phi = power(e, m, area);
                if (!(phi > 0)) continue;
                lightOfInstanced_[static_cast<uint64_t>(id) << 32 | k] =
                    static_cast<uint32_t>(lights_.size());
                addBounded(e, LightBounds::surface(lb.lo, lb.hi, phi, e.n, !e.frontOnly));
            }
            continue;
        }
        if (!emits(id)) continue;
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
            LightBounds lb;
            if (!triangleEntry(e, Vec3(v[0]), Vec3(v[1]), Vec3(v[2]), lb, area)) continue;
            lo = lb.lo;
            hi = lb.hi;
            normal = e.n;
        } else {
            const Bounds3f box = prims.bounds(id);
            lo = Vec3(box.lo);
            hi = Vec3(box.hi);
            if (prims.isSphere(id)) {
                e.kind = Kind::Sphere;
                const Sphere& s = prims.sphere(id - prims.triangleCount());
                area = approximateArea(s);
                std::tie(e.center, e.radius) = roundSphere(s);
            } else {
                e.kind = Kind::Shape;
                area =
                    approximateArea(prims.shape(id - prims.triangleCount() - prims.sphereCount()));
            }
        }
        const double phi = power(e, m, area);
        if (!(phi > 0)) continue;
        lightOfPrimitive_[id] = static_cast<uint32_t>(lights_.size());
        // A sphere or shape emits about every normal; a triangle about its own, from both
        // sides unless front-only.
        addBounded(e, LightBounds::surface(lo, hi, phi, normal, !e.frontOnly));
    }

    // Emissive planes: radiance L over a half-space of directions gives pi L at any distance.
    for (uint32_t id = boundedCount; id < prims.size(); ++id) {
        const Material& m = scene.materials[prims.materialOf(id)];
        if (!(brightness(m.emission) > 0)) continue;
        const Plane& plane = prims.plane(id);
        Entry e{Kind::Plane, id, m.frontEmissionOnly};
        e.emission = m.emission;
        e.c = plane.point;
        e.n = plane.normal;
        if (lightOfPrimitive_.size() < prims.size())
            lightOfPrimitive_.resize(prims.size(), UINT32_MAX);
        lightOfPrimitive_[id] = static_cast<uint32_t>(lights_.size());
        addInfinite(e, kPi * kPi * brightness(m.emission));
    }

    // The environment map, or the background if it is not black: its mean radiance L gives
    // pi L from a hemisphere.
    const double meanRadiance =
        brightness(scene.environment ? scene.environment->averageRadiance()
                                     : (scene.background.down + scene.background.up) * 0.5);
    if (meanRadiance > 0) {
        environment_ = static_cast<uint32_t>(lights_.size());
        addInfinite({Kind::Environment, 0}, kPi * kPi * meanRadiance);
        if (scene.environment) passShareOfMap(*scene.environment);
    }

    tree_ = LightTree(bounded);
    treeLeafOf_.assign(lights_.size(), UINT32_MAX);
    for (uint32_t k = 0; k < lightOfTreeLeaf_.size(); ++k) treeLeafOf_[lightOfTreeLeaf_[k]] = k;
}

void LightSampler::passShareOfMap(const EnvironmentMap& map) {
    // Several times the mean: a sun's disc or a lamp's, not a bright sky.
    constexpr double kAboveMean = 4;
    passThreshold_ = kAboveMean * luminance(map.averageRadiance());
    double above = 0, all = 0;
    for (int y = 0; y < map.height(); ++y) {
        // Texels of a row subtend the same solid angle, in proportion to the sine there.
        const double sinTheta = std::sin(kPi * (y + 0.5) / map.height());
        for (int x = 0; x < map.width(); ++x) {
            const double l = luminance(map.texel(x, y) * map.scale()) * sinTheta;
            all += l;
            if (l > passThreshold_ * sinTheta) above += l;
        }
    }
    passShare_ = all > 0 ? above / all : 0;
}

double LightSampler::pInfinite(const Vec3& p, const Vec3& n) const {
    if (infinite_.empty()) return 0;
    if (tree_.empty()) return 1;
    const double tree = tree_.importance(p, n);
    return infiniteTotal_ / (infiniteTotal_ + tree);
}

std::optional<LightSample> LightSampler::sample(const Vec3& p, const Vec3& n, double uLight,
                                                Point2 u) const {
    if (lights_.empty()) return std::nullopt;
    uint32_t index;
    double choice;
    const double pInf = pInfinite(p, n);
    if (uLight < pInf) {
        // By weight, in order: there are few.
        double at = uLight / pInf * infiniteTotal_;
        size_t k = 0;
        while (k + 1 < infinite_.size() && at >= lights_[infinite_[k]].weight)
            at -= lights_[infinite_[k++]].weight;
        index = infinite_[k];
        choice = pInf * lights_[index].weight / infiniteTotal_;
    } else {
        const double v = std::min((uLight - pInf) / (1 - pInf), 0x1.fffffffffffffp-1);
        std::optional<LightTree::Choice> c = tree_.sample(p, n, v);
        if (!c) return std::nullopt;
        index = lightOfTreeLeaf_[c->light];
        choice = (1 - pInf) * c->probability;
    }
    const Entry& e = lights_[index];
    std::optional<LightSample> s = sampleEntry(e, p, u);
    if (!s) return s;
    s->pdf *= choice;
    s->leftToPass =
        e.kind == Kind::Environment ? environmentLeftToPass(s->L) : e.kind != Kind::Plane;
    return s;
}

double LightSampler::choiceProbability(size_t index, const Vec3& p, const Vec3& n) const {
    if (index >= lights_.size()) return 0;
    const uint32_t leaf = treeLeafOf_[index];
    if (leaf != UINT32_MAX) return (1 - pInfinite(p, n)) * tree_.pmf(p, n, leaf);
    return pInfinite(p, n) * lights_[index].weight / infiniteTotal_;
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
        case Kind::Plane: {
            // Cosine-weighted about the normal, over the directions that meet the plane.
            const double side = dot(p - e.c, e.n);
            if (side == 0 || (e.frontOnly && side < 0)) return std::nullopt;
            const Frame frame(side > 0 ? -e.n : e.n);
            const Vec3 local = sampleCosineHemisphere(u);
            if (!(local.z > 0)) return std::nullopt;
            const Vec3 wi = normalize(frame.toWorld(local));
            return LightSample{wi, e.emission, local.z / kPi, std::abs(side) / local.z, false};
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
        if (const SphericalTriangle t = sphericalTriangle(e, p); t.solidAngle > 0)
            return sampleTriangleSolidAngle(e, p, u, t);
        auto [b0, b1] = sampleUniformTriangle(u);  // as sampleTriangle, from stored edges
        ss = {e.c + e.ca * b0 + e.cb * b1, e.n, e.pdfArea};
        if (e.texturedPbr != 0)  // the point is a b0 + b b1 + c (1 - b0 - b1)
            emission = texturedEmission(e, b1, 1 - b0 - b1);
    } else if (e.kind == Kind::Sphere) {
        if (std::optional<LightSample> s = sampleSphereCone(e, p, u)) return s;
        if (outsideSphere(dot(p - e.center, p - e.center), e.radius))
            return std::nullopt;  // from outside, the cone was the way: nothing arrives
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

LightSampler::SphericalTriangle LightSampler::sphericalTriangle(const Entry& e, const Vec3& p) {
    // pbrt-v4's range: below, the triangle is small or far enough that area sampling is as
    // good and the spherical construction loses digits; above, nearly a hemisphere.
    constexpr double kMin = 3e-4, kMax = 6.22;
    const Vec3 a = e.c + e.ca - p, b = e.c + e.cb - p, c = e.c - p;
    const double la = length(a), lb = length(b), lc = length(c);
    if (!(la > 0 && lb > 0 && lc > 0)) return {};
    SphericalTriangle t{a / la, b / lb, c / lc, 0};
    const double area = sphericalTriangleArea(t.a, t.b, t.c);
    if (area >= kMin && area <= kMax) t.solidAngle = area;
    return t;
}

std::optional<LightSample> LightSampler::sampleTriangleSolidAngle(
    const Entry& e, const Vec3& p, Point2 u, const SphericalTriangle& t) const {
    const std::optional<Vec3> wi = sampleSphericalTriangle(t.a, t.b, t.c, u);
    if (!wi) return std::nullopt;
    const double cosLight = dot(*wi, e.n);  // < 0: the light's front faces p
    if (e.frontOnly ? !(cosLight < 0) : cosLight == 0) return std::nullopt;
    const double dist = dot(e.c - p, e.n) / cosLight;  // to the triangle's plane
    if (!(dist > 0) || !std::isfinite(dist)) return std::nullopt;
    Vec3 emission = e.emission;
    if (e.texturedPbr != 0) {  // the point's barycentrics: of a (b0) and of b (b1)
        const Vec3 q = p + *wi * dist - e.c;
        const double twiceArea = 2 / e.pdfArea;
        const double b0 = dot(cross(q, e.cb), e.n) / twiceArea;
        const double b1 = dot(cross(e.ca, q), e.n) / twiceArea;
        emission = texturedEmission(e, b1, 1 - b0 - b1);
    }
    return LightSample{*wi, emission, 1 / t.solidAngle, dist, false};
}

std::optional<LightSample> LightSampler::sampleSphereCone(const Entry& e, const Vec3& p,
                                                          Point2 u) const {
    const Vec3 toCenter = e.center - p;
    const double d2 = dot(toCenter, toCenter);
    if (!outsideSphere(d2, e.radius)) return std::nullopt;
    // A direction within the cone, uniformly: its angle theta from the axis, then the point
    // of the sphere it meets first, by the angle alpha at the centre (pbrt-v4's derivation).
    double sin2Max;
    const double oneMinusCosMax = oneMinusCosCone(e.radius, d2, &sin2Max);
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
    const Vec3 q = e.center + normal * e.radius;
    const Vec3 d = q - p;
    const double dist = length(d);
    if (!(dist > 0)) return std::nullopt;
    const double pdf = 1 / (2 * kPi * oneMinusCosMax);
    if (!std::isfinite(pdf)) return std::nullopt;
    return LightSample{d / dist, e.emission, pdf, dist, false};
}

Vec3 LightSampler::texturedEmission(const Entry& e, double b1, double b2) const {
    const Primitives& prims = scene_.primitives;
    const SurfaceInteraction at =
        e.sub == UINT32_MAX
            ? prims.triangleAttributes(e.index, b1, b2)
            : prims.sharedMesh(prims.instanceMesh(e.index)).triangleAttributes(e.sub, b1, b2);
    return emissionAt(scene_.pbr(e.texturedPbr), at);
}

double LightSampler::pdfHit(const Vec3& from, const Vec3& fromN, const Hit& hit,
                            const SurfaceInteraction& si) const {
    uint32_t index = UINT32_MAX;
    if (!lightOfInstanced_.empty() && scene_.primitives.isInstance(hit.primId)) {
        const auto it = lightOfInstanced_.find(static_cast<uint64_t>(hit.primId) << 32 | hit.subId);
        if (it != lightOfInstanced_.end()) index = it->second;
    } else if (hit.primId < lightOfPrimitive_.size()) {
        index = lightOfPrimitive_[hit.primId];
    }
    if (index == UINT32_MAX) return 0;
    const Entry& e = lights_[index];
    const Primitives& prims = scene_.primitives;
    if (e.kind == Kind::Plane) {
        const double side = dot(from - e.c, e.n);
        if (side == 0 || (e.frontOnly && side < 0)) return 0;
        const double cosPlane = std::abs(dot(normalize(si.p - from), e.n));
        return choiceProbability(index, from, fromN) * cosPlane / kPi;
    }
    double pdfArea = e.pdfArea;
    if (e.kind == Kind::Triangle)
        if (const double solidAngle = sphericalTriangle(e, from).solidAngle; solidAngle > 0)
            return choiceProbability(index, from, fromN) / solidAngle;
    if (e.kind == Kind::Sphere) {
        const double d2 = dot(e.center - from, e.center - from);
        if (outsideSphere(d2, e.radius)) {  // sampled by its cone
            double sin2Max;
            return choiceProbability(index, from, fromN) /
                   (2 * kPi * oneMinusCosCone(e.radius, d2, &sin2Max));
        }
        pdfArea = spherePdfArea(prims.sphere(e.index - prims.triangleCount()), si.ng);
    } else if (e.kind == Kind::Shape)
        pdfArea =
            shapePdfArea(prims.shape(e.index - prims.triangleCount() - prims.sphereCount()), si.ng);
    Vec3 d = si.p - from;
    double d2 = dot(d, d);
    double cosLight = std::abs(dot(d, si.ng)) / std::sqrt(d2);
    if (!(cosLight > 0)) return 0;
    return choiceProbability(index, from, fromN) * pdfArea * d2 / cosLight;
}

Vec3 LightSampler::environment(const Vec3& dir, const Vec3& from, const Vec3& fromN,
                               double* pdf) const {
    if (!scene_.environment) {
        *pdf = pdfEnvironment(dir, from, fromN);
        return scene_.background.eval(dir);
    }
    const EnvironmentMap& map = *scene_.environment;
    const Point2 st = map.imageCoordinates(dir);
    *pdf = environment_ == UINT32_MAX
               ? 0
               : choiceProbability(environment_, from, fromN) * map.pdfAt(st);
    return map.evalAt(st);
}

double LightSampler::pdfEnvironment(const Vec3& dir, const Vec3& from, const Vec3& fromN) const {
    if (environment_ == UINT32_MAX) return 0;
    double pdf = scene_.environment ? scene_.environment->pdf(dir) : 1 / (4 * kPi);
    return choiceProbability(environment_, from, fromN) * pdf;
}

}  // namespace glint

namespace glint {
namespace {

/// A direction drawn uniformly over the cone of directions that the sphere (`center`,
/// `radius`) fills from `p`, or over every direction from inside it, and its density.
std::pair<Vec3, double> sampleTowardsSphere(const Vec3& p, const Vec3& center, double radius,
                                            Point2 u) {
    const Vec3 toCenter = center - p;
    const double d2 = dot(toCenter, toCenter);
    if (!outsideSphere(d2, radius)) return {sampleUniformSphere(u), 1 / (4 * kPi)};
    double sin2Max;
    const double oneMinusCos = oneMinusCosCone(radius, d2, &sin2Max);
    const double cosTheta = 1 - u.x * oneMinusCos;
    const double sinTheta = std::sqrt(std::max(0.0, 1 - cosTheta * cosTheta));
    const double phi = 2 * kPi * u.y;
    const Frame frame(toCenter / std::sqrt(d2));
    const Vec3 dir = frame.toWorld({sinTheta * std::cos(phi), sinTheta * std::sin(phi), cosTheta});
    return {normalize(dir), 1 / (2 * kPi * oneMinusCos)};
}

/// The solid angle the sphere fills from `p` (4 pi from inside).
double solidAngleOfSphere(const Vec3& p, const Vec3& center, double radius) {
    const double d2 = dot(center - p, center - p);
    if (!outsideSphere(d2, radius)) return 4 * kPi;
    double sin2Max;
    return 2 * kPi * oneMinusCosCone(radius, d2, &sin2Max);
}

}  // namespace

std::vector<double> LightSampler::emissionWeights(const Vec3& center, double radius) const {
    std::vector<double> w(lights_.size(), 0.0);
    for (size_t i = 0; i < lights_.size(); ++i) {
        const Entry& e = lights_[i];
        if (treeLeafOf_[i] == UINT32_MAX) {  // at infinity: weight / pi is its irradiance
            const double share = e.kind == Kind::Environment ? passShare_
                                 : e.kind == Kind::Plane     ? 0
                                                             : 1;
            w[i] = e.weight * share * radius * radius;
            continue;
        }
        w[i] =
            e.power * std::min(solidAngleOfSphere(e.middle, center, radius), 2 * kPi) / (2 * kPi);
    }
    return w;
}

std::optional<EmittedRay> LightSampler::emit(size_t index, const Vec3& center, double radius,
                                             double far, Point2 uPoint, Point2 uDir) const {
    const Entry& e = lights_[index];
    const Primitives& prims = scene_.primitives;
    // Lights at infinity: across the sphere's disc, uniformly (density 1 / (pi r^2)).
    auto acrossDisc = [&](const Vec3& towardsLight, const Vec3& radiance,
                          double pdfDir) -> std::optional<EmittedRay> {
        const auto [dx, dy] = sampleUniformDisk(uPoint.x, uPoint.y);
        const Frame frame(towardsLight);
        const Vec3 origin = center + towardsLight * far + (frame.t * dx + frame.b * dy) * radius;
        return EmittedRay{Ray{origin, -towardsLight, 0, kInfinity},
                          radiance * (kPi * radius * radius / pdfDir)};
    };
    switch (e.kind) {
        case Kind::Directional: {
            const Light& l = scene_.lights[e.index];
            return acrossDisc(l.direction, l.color, 1);
        }
        case Kind::Environment: {
            // Its bright parts only (environmentLeftToPass); a plain background not at all.
            if (!scene_.environment) return std::nullopt;
            std::optional<EnvironmentMap::Sample> s = scene_.environment->sample(uDir);
            if (!s || !(s->pdf > 0) || !environmentLeftToPass(s->L)) return std::nullopt;
            return acrossDisc(s->wi, s->L, s->pdf);
        }
        case Kind::Plane:  // large: the camera's paths' (environmentLeftToPass)
            return std::nullopt;
        case Kind::Point: {
            const Light& l = scene_.lights[e.index];
            const auto [dir, pdf] = sampleTowardsSphere(l.position, center, radius, uDir);
            return EmittedRay{Ray{l.position, dir, 0, kInfinity}, l.color / pdf, &l};
        }
        default:
            break;
    }
    SurfaceSample ss;
    Vec3 emission = e.emission;
    if (e.kind == Kind::Triangle) {
        auto [b0, b1] = sampleUniformTriangle(uPoint);
        ss = {e.c + e.ca * b0 + e.cb * b1, e.n, e.pdfArea};
        if (e.texturedPbr != 0) emission = texturedEmission(e, b1, 1 - b0 - b1);
    } else if (e.kind == Kind::Sphere) {
        ss = sampleSphere(prims.sphere(e.index - prims.triangleCount()), uPoint);
    } else {
        ss =
            sampleShape(prims.shape(e.index - prims.triangleCount() - prims.sphereCount()), uPoint);
    }
    if (!(ss.pdfArea > 0)) return std::nullopt;
    const auto [dir, pdfDir] = sampleTowardsSphere(ss.p, center, radius, uDir);
    const double cosLight = dot(dir, ss.n);
    if (e.frontOnly ? !(cosLight > 0) : cosLight == 0) return std::nullopt;
    const Vec3 beta = emission * (std::abs(cosLight) / (ss.pdfArea * pdfDir));
    return EmittedRay{spawnRayOffSurface(ss.p, ss.n, dir, scene_.spawnOffset()), beta};
}

}  // namespace glint
