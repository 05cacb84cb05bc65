#include "glint/render/path.h"

#include <cmath>

#include "glint/core/spawn.h"
#include "glint/math/sobol.h"
#include "glint/render/bsdf.h"

namespace glint {
namespace {

/// The power heuristic with exponent 2 for a sample drawn with density `a` by the one strategy
/// and `b` by the other.
inline double powerHeuristic(double a, double b) {
    double a2 = a * a, b2 = b * b;
    return a2 > 0 ? a2 / (a2 + b2) : 0;
}

/// Whether every lobe of `bsdf` is a delta: no light sample can meet it.
bool specularOnly(const Bsdf& bsdf) {
    struct Visitor {
        bool operator()(const Lambertian&) const { return false; }
        bool operator()(const Conductor& c) const { return c.alpha == 0; }
        bool operator()(const Dielectric& d) const { return !d.rough(); }
        bool operator()(const DiffuseSpecular& d) const {
            return d.alpha == 0 && d.diffuse == Vec3(0);
        }
    };
    return std::visit(Visitor{}, bsdf.lobe);
}

}  // namespace

PathIntegrator::PathIntegrator(const Scene& scene, Strategy strategy)
    : scene_(scene), lights_(scene), strategy_(strategy) {
    bsdfs_.reserve(scene.materials.size());
    for (const Material& m : scene.materials) bsdfs_.push_back(bsdfFromMaterial(m));
    if (scene.shadowCatcher) catcher_.emplace(scene);
}

double PathIntegrator::bsdfWeight(double bsdfPdf, double lightPdf) const {
    switch (strategy_) {
        case Strategy::Mis:
            return powerHeuristic(bsdfPdf, lightPdf);
        case Strategy::LightsOnly:
            return lightPdf > 0 ? 0 : 1;  // lights not sampled count in full
        default:
            return 1;
    }
}

Vec3 PathIntegrator::li(const Ray& cameraRay, const Hit* cameraHit, PathContext& ctx) const {
    SobolSampler sampler(ctx.pixelSeed, ctx.sampleIndex);
    const double offset = scene_.spawnOffset();
    Vec3 L(0), beta(1);
    bool specularBounce = false;
    double bsdfPdf = 0;  // density of the direction the last bounce drew
    Vec3 from;           // where it left from
    Ray ray = cameraRay;
    Hit hit;
    bool found = cameraHit != nullptr;
    if (found) hit = *cameraHit;

    for (int depth = 0;; ++depth) {
        // A shadow catcher is seen by camera rays and their specular continuations only.
        if (catcher_ && (depth == 0 || specularBounce)) [[unlikely]] {
            std::optional<double> t = catcher_->intersect(ray);
            if (t && (!found || *t < hit.t)) {
                const Point2 uEnvironment = sampler.get2D();
                const double uLight = sampler.get2D().x;
                L += beta * catcher_->radiance(ray.origin + ray.dir * *t, normalize(ray.dir),
                                               uEnvironment, uLight, ctx.counts);
                break;
            }
        }
        if (!found) {
            double lightPdf = 0;
            Vec3 le = lights_.environment(ray.dir, &lightPdf);
            if (depth == 0 || specularBounce)
                L += beta * le;
            else if (!(le == Vec3(0)))
                L += beta * le * bsdfWeight(bsdfPdf, lightPdf);
            break;
        }
        const SurfaceInteraction si = scene_.primitives.interaction(ray, hit);
        const Material& m = scene_.materials[si.material];

        // Light the surface emits towards the path.
        if (!(m.emission == Vec3(0)) && (!m.frontEmissionOnly || dot(ray.dir, si.ng) < 0)) {
            if (depth == 0 || specularBounce)
                L += beta * m.emission;
            else
                L += beta * m.emission * bsdfWeight(bsdfPdf, lights_.pdfHit(from, hit, si));
        }
        if (depth >= scene_.maxDepth) break;

        Bsdf bsdf;
        if (m.texture != 0) {
            Material textured = m;
            textured.diffuse =
                scene_.texture(m.texture).eval(si.hasUv, si.u, si.v, si.p, m.diffuse);
            bsdf = bsdfFromMaterial(textured);
        } else {
            bsdf = bsdfFromMaterial(m);
        }
        // The shading frame's normal on the geometric normal's side, so that the side a
        // direction lies on (inside or outside a dielectric) is the geometry's.
        const Frame frame(dot(si.n, si.ng) < 0 ? -si.n : si.n);
        const Vec3 wo = frame.toLocal(-ray.dir);

        // Next-event estimation: one light sample, weighted against the BSDF's density.
        // Three pairs of dimensions per bounce: (light, lobe), the point on the light, the
        // BSDF's direction; Russian roulette takes the sample's own random numbers.
        const Point2 uChoices = sampler.get2D();
        const double uLight = uChoices.x;
        const Point2 uLightPoint = sampler.get2D();
        if (!lights_.empty() && !specularOnly(bsdf)) {
            std::optional<LightSample> ls = lights_.sample(si.p, uLight, uLightPoint);
            // BSDF sampling alone cannot reach delta lights: they are sampled in every mode.
            if (ls && !(ls->L == Vec3(0)) && (ls->delta || strategy_ != Strategy::BsdfOnly)) {
                Vec3 wi = frame.toLocal(ls->wi);
                Vec3 f = bsdf.eval(wo, wi) * std::abs(wi.z);
                if (!(f == Vec3(0))) {
                    double end = ls->distance;
                    if (std::isfinite(end))  // back off at the light's end: its surface lies there
                        end -= spawnOffset(si.p + ls->wi * end, offset);
                    ctx.counts.shadow++;
                    if (!scene_.bvh().occluded(spawnRay(si.p, ls->wi, offset, end))) {
                        double w = ls->delta || strategy_ == Strategy::LightsOnly
                                       ? 1
                                       : powerHeuristic(ls->pdf, bsdf.pdf(wo, wi));
                        L += beta * f * ls->L * (w / ls->pdf);
                    }
                }
            }
        }

        // The next direction, from the BSDF.
        const double uLobe = uChoices.y;
        const Point2 uDir = sampler.get2D();
        std::optional<BsdfSample> bs = bsdf.sample(wo, uLobe, uDir);
        if (!bs || !(bs->pdf > 0)) break;
        beta = beta * bs->weight();
        if (beta == Vec3(0)) break;
        specularBounce = bs->isSpecular();
        bsdfPdf = bs->pdf;
        from = si.p;

        // Russian roulette from the second bounce on: a path of throughput below 1 survives
        // with probability equal to it, and is reweighted so the estimate stays unbiased.
        double survive = maxComponent(beta);
        if (depth >= 1 && survive < 1) {
            if (ctx.rng.uniform() >= survive) break;
            beta = beta / survive;
        }

        ray = spawnRay(si.p, normalize(frame.toWorld(bs->wi)), offset);
        ctx.counts.reflection++;
        hit = Hit{};
        found = scene_.bvh().intersect(ray, hit);
    }
    return finiteRadiance(L, ctx.counts);
}

}  // namespace glint
