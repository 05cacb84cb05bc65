// Area lights through the real renderer and Whitted integrator: a white-lit diffuse floor under
// a quad light, each pixel's radiance against kd x the analytic irradiance at its point.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>

#include "glint/render/renderer.h"
#include "unit/scene/quad_light_support.h"
#include "unit/statistics.h"
#include "unit/test_support.h"

namespace glint {
namespace {

const Vec3 kDiffuse{0.7, 0.5, 0.3};
const Vec3 kRadiance{2, 3, 4};

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
    Light l = test::quadLight({-0.6, 1.2, -0.4}, {1.2, 0.1, 0}, {0.2, 0, 0.8});
    l.color = kRadiance;
    scene->lights.push_back(l);
    Material m = test::makeMaterial(Vec3(0));
    m.emission = l.color;
    m.frontEmissionOnly = true;
    uint32_t id = scene->addMaterial(m);
    Vec3 c[4] = {l.position, l.position + l.edge1, l.position + l.edge1 + l.edge2,
                 l.position + l.edge2};
    scene->primitives.addTriangle(c[0], c[1], c[2], nullptr, id);
    scene->primitives.addTriangle(c[0], c[2], c[3], nullptr, id);
    scene->prepare();
    return scene;
}

TEST(AreaLight, WhittedPixelsAreDiffuseTimesTheAnalyticIrradianceOnAverage) {
    for (int grid : {1, 4}) {
        std::unique_ptr<Scene> scene = floorUnderQuadLight(grid);
        const Light& light = scene->lights[0];
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

}  // namespace
}  // namespace glint
