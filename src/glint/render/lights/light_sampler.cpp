#include "glint/render/lights/light_sampler.h"

#include <algorithm>
#include <cmath>

#include "glint/render/lights/light_util.h"

namespace glint {

using namespace light_util;

LightSampler::LightSampler(const Scene& scene) : scene_(scene) {
    const Primitives& prims = scene.primitives;
    std::vector<LightBounds> bounded;
    auto addBounded = [&](const Light& light) {
        lightOfTreeLeaf_.push_back(static_cast<uint32_t>(lights_.size()));
        bounded.push_back(*light.bounds());
        lights_.push_back(light);
        infiniteWeight_.push_back(0);
    };
    // A light at infinity's weight is the irradiance it gives a surface facing it, times pi
    // as the light tree's importance has it (a Lambertian emitter of power phi gives pi times
    // the irradiance at normal incidence).
    auto addInfinite = [&](const Light& light) {
        const double weight = light.infiniteImportance();
        infinite_.push_back(static_cast<uint32_t>(lights_.size()));
        infiniteTotal_ += weight;
        lights_.push_back(light);
        infiniteWeight_.push_back(weight);
    };

    // The scene's own lights, but the quads: their emissive triangles below stand for them.
    // A few delta lights are each sampled, not chosen (see the header).
    const size_t deltas = std::count_if(scene.lights.begin(), scene.lights.end(),
                                        [](const LightSpec& s) { return s.isDelta(); });
    const bool each = deltas >= 2 && deltas <= kEachDelta;
    for (const LightSpec& spec : scene.lights) {
        if (spec.kind == LightSpec::Kind::Quad) continue;
        const Light light = lightFromSpec(spec);
        if (each) {
            each_.push_back(static_cast<uint32_t>(lights_.size()));
            lights_.push_back(light);
            infiniteWeight_.push_back(0);
            continue;
        }
        if (light.bounds())
            addBounded(light);
        else if (light.infiniteImportance() > 0)
            addInfinite(light);
    }

    // Emissive surfaces.
    auto emits = [&](uint32_t id) {
        uint32_t m = prims.materialOf(id);
        return m != Primitives::kMixedMaterials && brightness(scene.materials[m].emission) > 0;
    };
    const uint32_t boundedCount = prims.boundedCount();
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
                const PbrMaterial* texture =
                    m.pbr != 0 && scene.pbr(m.pbr).emissiveTexture ? &scene.pbr(m.pbr) : nullptr;
                auto v = mesh.triangleVertices(k);
                std::optional<TriangleLight> light = TriangleLight::make(
                    t.point(Vec3(v[0])), t.point(Vec3(v[1])), t.point(Vec3(v[2])), m.emission,
                    m.frontEmissionOnly, texture, &mesh, k);
                if (!light) continue;
                lightOfInstanced_[static_cast<uint64_t>(id) << 32 | k] =
                    static_cast<uint32_t>(lights_.size());
                addBounded(*light);
            }
            continue;
        }
        if (!emits(id)) continue;
        if (lightOfPrimitive_.empty()) lightOfPrimitive_.assign(boundedCount, UINT32_MAX);
        const Material& m = scene.materials[prims.materialOf(id)];
        std::optional<Light> light;
        if (id < prims.triangleCount()) {
            const PbrMaterial* texture =
                m.pbr != 0 && scene.pbr(m.pbr).emissiveTexture ? &scene.pbr(m.pbr) : nullptr;
            auto v = prims.triangleVertices(id);
            if (std::optional<TriangleLight> t =
                    TriangleLight::make(Vec3(v[0]), Vec3(v[1]), Vec3(v[2]), m.emission,
                                        m.frontEmissionOnly, texture, &prims, id))
                light = *t;
        } else {
            const Bounds3f box = prims.bounds(id);
            const Vec3 lo(box.lo), hi(box.hi);
            if (prims.isSphere(id)) {
                SphereLight s = SphereLight::make(prims.sphere(id - prims.triangleCount()), lo, hi,
                                                  m.emission, m.frontEmissionOnly);
                if (s.phi > 0) light = s;
            } else {
                ShapeLight s =
                    ShapeLight::make(prims.shape(id - prims.triangleCount() - prims.sphereCount()),
                                     lo, hi, m.emission, m.frontEmissionOnly);
                if (s.phi > 0) light = s;
            }
        }
        if (!light) continue;
        lightOfPrimitive_[id] = static_cast<uint32_t>(lights_.size());
        addBounded(*light);
    }

    // Emissive planes.
    for (uint32_t id = boundedCount; id < prims.size(); ++id) {
        const Material& m = scene.materials[prims.materialOf(id)];
        if (!(brightness(m.emission) > 0)) continue;
        const Plane& plane = prims.plane(id);
        if (lightOfPrimitive_.size() < prims.size())
            lightOfPrimitive_.resize(prims.size(), UINT32_MAX);
        lightOfPrimitive_[id] = static_cast<uint32_t>(lights_.size());
        addInfinite(PlaneLight{plane.point, plane.normal, m.emission, m.frontEmissionOnly});
    }

    // The environment map, or the background if it is not black.
    EnvironmentLight sky = EnvironmentLight::make(scene.environment.get(), scene.background);
    if (sky.infiniteImportance() > 0) {
        environment_ = static_cast<uint32_t>(lights_.size());
        addInfinite(sky);
    }

    tree_ = LightTree(bounded);
    treeLeafOf_.assign(lights_.size(), UINT32_MAX);
    for (uint32_t k = 0; k < lightOfTreeLeaf_.size(); ++k) treeLeafOf_[lightOfTreeLeaf_[k]] = k;
}

double LightSampler::pInfinite(const Vec3& p, const Vec3& n) const {
    if (infinite_.empty()) return 0;
    if (tree_.empty()) return 1;
    const double tree = tree_.importance(p, n);
    return infiniteTotal_ / (infiniteTotal_ + tree);
}

std::optional<LightSample> LightSampler::sample(const Vec3& p, const Vec3& n, double uLight,
                                                Point2 u) const {
    if (!choosesAny()) return std::nullopt;
    uint32_t index;
    double choice;
    const double pInf = pInfinite(p, n);
    if (uLight < pInf) {
        // By weight, in order: there are few.
        double at = uLight / pInf * infiniteTotal_;
        size_t k = 0;
        while (k + 1 < infinite_.size() && at >= infiniteWeight_[infinite_[k]])
            at -= infiniteWeight_[infinite_[k++]];
        index = infinite_[k];
        choice = pInf * infiniteWeight_[index] / infiniteTotal_;
    } else {
        const double v = std::min((uLight - pInf) / (1 - pInf), 0x1.fffffffffffffp-1);
        std::optional<LightTree::Choice> c = tree_.sample(p, n, v);
        if (!c) return std::nullopt;
        index = lightOfTreeLeaf_[c->light];
        choice = (1 - pInf) * c->probability;
    }
    const Light& light = lights_[index];
    std::optional<LightLiSample> s = light.sampleLi(p, u);
    if (!s) return std::nullopt;
    return LightSample{s->wi,       s->L,     s->pdf * choice,
                       s->distance, s->delta, light.tracedByLightPass(s->L)};
}

double LightSampler::choiceProbability(size_t index, const Vec3& p, const Vec3& n) const {
    if (index >= lights_.size()) return 0;
    if (std::find(each_.begin(), each_.end(), index) != each_.end()) return 1;  // sampled each
    const uint32_t leaf = treeLeafOf_[index];
    if (leaf != UINT32_MAX) return (1 - pInfinite(p, n)) * tree_.pmf(p, n, leaf);
    return pInfinite(p, n) * infiniteWeight_[index] / infiniteTotal_;
}

double LightSampler::pdfHit(const Vec3& from, const Vec3& fromN, const Vec3& dir, const Hit& hit,
                            const SurfaceInteraction& si) const {
    uint32_t index = UINT32_MAX;
    if (!lightOfInstanced_.empty() && scene_.primitives.isInstance(hit.primId)) {
        const auto it = lightOfInstanced_.find(static_cast<uint64_t>(hit.primId) << 32 | hit.subId);
        if (it != lightOfInstanced_.end()) index = it->second;
    } else if (hit.primId < lightOfPrimitive_.size()) {
        index = lightOfPrimitive_[hit.primId];
    }
    if (index == UINT32_MAX) return 0;
    return lights_[index].pdfLi(from, LightPoint{si.p, si.ng, dir},
                                choiceProbability(index, from, fromN));
}

Vec3 LightSampler::environment(const Vec3& dir, const Vec3& from, const Vec3& fromN,
                               double* pdf) const {
    if (environment_ == UINT32_MAX) {
        *pdf = 0;
        return environment(dir);
    }
    return lights_[environment_].as<EnvironmentLight>()->radiance(
        dir, pdf, choiceProbability(environment_, from, fromN));
}

double LightSampler::pdfEnvironment(const Vec3& dir, const Vec3& from, const Vec3& fromN) const {
    if (environment_ == UINT32_MAX) return 0;
    return lights_[environment_].pdfLi(from, LightPoint{Vec3(0), Vec3(0), dir},
                                       choiceProbability(environment_, from, fromN));
}

std::vector<double> LightSampler::emissionWeights(const Vec3& center, double radius) const {
    std::vector<double> w(lights_.size(), 0.0);
    for (size_t i = 0; i < lights_.size(); ++i) {
        const Light& light = lights_[i];
        if (treeLeafOf_[i] == UINT32_MAX) {  // at infinity: weight / pi is its irradiance
            w[i] = infiniteWeight_[i] * light.lightPassShare() * radius * radius;
            continue;
        }
        const LightBounds b = *light.bounds();
        const Vec3 middle = (b.lo + b.hi) * 0.5;
        w[i] = b.phi * std::min(solidAngleOfSphere(middle, center, radius), 2 * kPi) / (2 * kPi);
    }
    return w;
}

}  // namespace glint
