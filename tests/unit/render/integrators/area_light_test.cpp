// Area lights through the real renderer and Whitted integrator: a white-lit diffuse floor under
// a quad light, each pixel's radiance against kd x the analytic irradiance at its point.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>

#include "glint/render/bsdfs/optics.h"
#include "glint/render/integrators/whitted.h"
#include "glint/render/renderer.h"
#include "unit/scene/quad_light_support.h"
#include "unit/statistics.h"
#include "unit/test_support.h"

namespace glint {
namespace {

const Vec3 kDiffuse{0.7, 0.5, 0.3};
const Vec3 kRadiance{2, 3, 4};

/// Adds the quad light `l` of radiance kRadiance with its emitting surface, as the course
/// loader does.
void addQuadLight(Scene& scene, LightSpec l) {
    l.color = kRadiance;
    scene.lights.push_back(l);
    Material m = test::makeMaterial(Vec3(0));
    m.emission = l.color;
    m.frontEmissionOnly = true;
    uint32_t id = scene.addMaterial(m);
    Vec3 c[4] = {l.position, l.position + l.edge1, l.position + l.edge1 + l.edge2,
                 l.position + l.edge2};
    scene.primitives.addTriangle(c[0], c[1], c[2], nullptr, id);
    scene.primitives.addTriangle(c[0], c[2], c[3], nullptr, id);
}

/// A diffuse floor (no ambient, no specular) and a sheared quad light above it facing down,
/// with its emitting surface as the course loader adds it; `grid` x `grid` shadow rays per
/// shading point. The camera sees the floor around the light and, near the top of the image,
/// the light's back.
std::unique_ptr<Scene> floorUnderQuadLight(int grid) {
    auto scene = std::make_unique<Scene>();
    scene->width = 16;
    scene->height = 12;
    scene->lightSamples = grid;
    scene->camera = CameraSpec{{0, 3, 3}, {0, 0, 0}, {0, 1, 0}, 40};
    uint32_t floor = scene->addMaterial(test::makeMaterial(Vec3(0), kDiffuse));
    scene->primitives.addTriangle({-5, 0, -5}, {-5, 0, 5}, {5, 0, 5}, nullptr, floor);
    scene->primitives.addTriangle({-5, 0, -5}, {5, 0, 5}, {5, 0, -5}, nullptr, floor);
    addQuadLight(*scene, test::quadLight({-0.6, 1.2, -0.4}, {1.2, 0.1, 0}, {0.2, 0, 0.8}));
    scene->prepare();
    return scene;
}

TEST(AreaLight, WhittedPixelsAreDiffuseTimesTheAnalyticIrradianceOnAverage) {
    for (int grid : {1, 4}) {
        std::unique_ptr<Scene> scene = floorUnderQuadLight(grid);
        const LightSpec& light = scene->lights[0];
        Camera camera(*scene->camera, scene->width, scene->height);
        test::MeanEstimate ratio;  // pixel / (kd L E), over floor pixels and seeds
        int floorPixels = 0;
        for (uint64_t seed = 1; seed <= 20; ++seed) {
            RenderOptions options;
            options.threads = 2;
            options.seed = seed;
            RenderResult r = render(*scene, options);
            for (int y = 0; y < scene->height; ++y)
                for (int x = 0; x < scene->width; ++x) {
                    // At one sample per pixel the camera ray goes through the pixel's centre.
                    Ray ray = camera.generateRay(x + 0.5, y + 0.5);
                    auto si = test::shoot(*scene, ray.origin, ray.dir);
                    ASSERT_TRUE(si);
                    const Vec3& pixel = r.film.at(x, y);
                    if (scene->materials[si->material].frontEmissionOnly) {  // the light's back
                        EXPECT_EQ(pixel, Vec3(0));
                        continue;
                    }
                    floorPixels += seed == 1;
                    double e = test::quadIrradiance(light, si->p, si->n);
                    // The course's diffuse term is kd E, without the 1/pi of a Lambertian BRDF.
                    // One estimate per pixel: the channels differ only by their colours.
                    double rx = pixel.x / (kDiffuse.x * kRadiance.x * e);
                    EXPECT_NEAR(pixel.z / (kDiffuse.z * kRadiance.z * e), rx, 1e-12 * rx);
                    ratio.add(rx);
                }
        }
        ASSERT_GT(floorPixels, 100);
        std::printf("%dx%d grid, %d floor pixels x 20 seeds: pixel / (kd L E) = %.5f +- %.5f\n",
                    grid, grid, floorPixels, ratio.mean(), ratio.standardError());
        EXPECT_NEAR(ratio.mean(), 1, 4 * ratio.standardError()) << "grid " << grid;
        // The estimates are usable ones: a 4 x 4 grid gives a few percent of noise per pixel.
        if (grid == 4) {
            EXPECT_LT(ratio.standardError() * std::sqrt(double(ratio.n)), 0.1);
        }
    }
}

/// A rough glossy sphere (no diffuse) under a quad light facing down, nothing else: its
/// GGX lobe's reflected ray meets the light or nothing.
std::unique_ptr<Scene> glossySphereUnderQuadLight(double roughness, int maxDepth) {
    auto scene = std::make_unique<Scene>();
    scene->lightSamples = 2;
    scene->maxDepth = maxDepth;
    Material glossy = test::makeMaterial(Vec3(0), Vec3(0), Vec3(0.8, 0.6, 0.4));
    glossy.roughness = roughness;
    scene->primitives.addSphere(Sphere{{0, 0, 0}, 1, {}}, scene->addMaterial(glossy));
    addQuadLight(*scene, test::quadLight({-0.5, 3, -0.5}, {1, 0, 0}, {0, 0, 1}));  // facing -y
    scene->prepare();
    return scene;
}

TEST(AreaLightGloss, TheHighlightIsWeighedBetweenLightSamplesAndTheGlossyRay) {
    // With maxdepth 0 no reflected ray is traced: the highlight comes from light samples
    // alone. With maxdepth 1 the reflected ray finds the light too, and multiple importance
    // sampling weighs the two: the same expected highlight, far less noise for a narrow lobe.
    for (double roughness : {0.05, 0.3}) {
        auto lightsOnly = glossySphereUnderQuadLight(roughness, 0);
        auto mis = glossySphereUnderQuadLight(roughness, 1);
        WhittedIntegrator a(*lightsOnly), b(*mis);
        // The point of the sphere that mirrors the light's centre towards the eye, found by
        // search along the meridian facing both, and two points beside it.
        const Vec3 eye(0, 0, 4), centre(0, 3, 0);
        Vec3 best;
        double bestCos = -2;
        for (int k = 0; k <= 9000; ++k) {
            double theta = k * (std::numbers::pi / 2) / 9000;
            Vec3 n(0, std::sin(theta), std::cos(theta));
            Vec3 r = reflect(normalize(n - eye), n);
            double c = dot(r, normalize(centre - n));
            if (c > bestCos) bestCos = c, best = n;
        }
        for (Vec3 target :
             {best, normalize(best + Vec3(0.05, 0, 0)), normalize(best + Vec3(0, 0.04, 0))}) {
            Ray ray{eye, normalize(target - eye), 0, kInfinity};
            Hit hit;
            ASSERT_TRUE(lightsOnly->bvh().intersect(ray, hit));
            test::MeanEstimate ea, eb;
            for (int i = 0; i < 20000; ++i) {
                RayCounts counts;
                PathContext ca{Rng(1000 + i), counts}, cb{Rng(900000 + i), counts};
                ea.add(a.li(ray, &hit, ca).y);
                eb.add(b.li(ray, &hit, cb).y);
            }
            EXPECT_NEAR(ea.mean(), eb.mean(),
                        5 * std::hypot(ea.standardError(), eb.standardError()))
                << "roughness " << roughness;
            EXPECT_GT(eb.mean(), 0);
            if (roughness < 0.1) {
                EXPECT_LT(eb.standardError(), 0.7 * ea.standardError())
                    << "no less noise from the glossy ray";
            }
        }
    }
}

}  // namespace
}  // namespace glint
