#include "glint/render/integrators/caustics.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <utility>
#include <vector>

#include "glint/core/parallel.h"
#include "glint/math/mat4.h"
#include "glint/render/integrators/path.h"
#include "glint/render/renderer.h"

namespace glint {
namespace {

constexpr double kPi = std::numbers::pi;

/// Two triangles of material `m`: the square [-half, half]^2 of the plane y = height, its
/// front (the triangles' winding) facing up or down.
void addSquare(Scene& scene, double height, double half, bool facingUp, uint32_t m) {
    const Vec3 a(-half, height, -half), b(half, height, -half), c(half, height, half),
        d(-half, height, half);
    if (facingUp) {
        scene.primitives.addTriangle(a, d, c, nullptr, m);
        scene.primitives.addTriangle(a, c, b, nullptr, m);
    } else {
        scene.primitives.addTriangle(a, b, c, nullptr, m);
        scene.primitives.addTriangle(a, c, d, nullptr, m);
    }
}

/// The mean of the image's pixels.
double meanOf(const Film& film) {
    double sum = 0;
    for (int y = 0; y < film.height(); ++y)
        for (int x = 0; x < film.width(); ++x) sum += film.at(x, y).x;
    return sum / (film.width() * film.height());
}

/// Over the 16 pixels that `chooser` (a render of other random numbers, so that the choice
/// favours neither image's noise) shows brightest, leaving out those above `most` (a light seen
/// directly): the sums of `a`'s and `b`'s red channel there.
std::pair<double, double> brightestSums(const Film& chooser, const Film& a, const Film& b,
                                        double most = kInfinity) {
    const int w = chooser.width();
    std::vector<std::pair<double, int>> order;
    for (int i = 0; i < w * chooser.height(); ++i)
        if (chooser.at(i % w, i / w).x <= most) order.push_back({chooser.at(i % w, i / w).x, i});
    std::sort(order.rbegin(), order.rend());
    double sumA = 0, sumB = 0;
    for (size_t k = 0; k < 16 && k < order.size(); ++k) {
        const int i = order[k].second;
        sumA += a.at(i % w, i / w).x;
        sumB += b.at(i % w, i / w).x;
    }
    return {sumA, sumB};
}

RenderOptions options(int spp, int threads = 2) {
    RenderOptions o;
    o.spp = spp;
    o.threads = threads;
    o.seed = 7;
    return o;
}

// A grey floor under a mirror ceiling, lit by a point light between them: the light the
// mirror sends down is that of the light's mirror image (the image source, as far above the
// mirror as the light is below it), which no camera path can find (a delta light seen in a
// delta mirror). With the scene's two bounces, each pixel of the floor is
// albedo / pi times the irradiance of the light and of its image: the light pass must add the
// image's, and with it off the image is the direct light alone.
TEST(CausticPass, AMirrorSendsDownThePointLightOfItsImage) {
    Scene scene;
    scene.integrator = "path";
    scene.maxDepth = 2;
    scene.width = scene.height = 16;
    scene.camera = CameraSpec{{0, 1.3, 1.6}, {0, 0, 0.2}, {0, 1, 0}, 30};
    Material floor;
    floor.diffuse = Vec3(0.5);
    Material mirror;
    mirror.specular = Vec3(1);
    const uint32_t fm = scene.addMaterial(floor);
    const uint32_t mm = scene.addMaterial(mirror);
    addSquare(scene, 0, 10, true, fm);
    addSquare(scene, 1.4, 5, false, mm);
    LightSpec lamp;
    lamp.position = Vec3(0.3, 1, 0.3);
    lamp.color = Vec3(1);
    lamp.attenuation = Vec3(0, 0, 1);  // physical: I / d^2
    scene.lights.push_back(lamp);
    scene.prepare();

    // The expected value at each pixel's centre (irradiance varies slowly across a pixel).
    const Camera camera(*scene.camera, scene.width, scene.height);
    const Vec3 image(0.3, 1.8, 0.3);  // the lamp mirrored in the plane y = 1.4
    auto irradiance = [](const Vec3& p, const Vec3& source) {
        const Vec3 d = source - p;
        const double d2 = dot(d, d);
        return d.y / std::sqrt(d2) / d2;
    };
    double direct = 0, mirrored = 0;
    for (int y = 0; y < scene.height; ++y)
        for (int x = 0; x < scene.width; ++x) {
            const Ray ray = camera.generateRay(x + 0.5, y + 0.5);
            ASSERT_LT(ray.dir.y, 0);
            const Vec3 p = ray.at(-ray.origin.y / ray.dir.y);
            direct += 0.5 / kPi * irradiance(p, lamp.position);
            mirrored += 0.5 / kPi * irradiance(p, image);
        }
    direct /= scene.width * scene.height;
    mirrored /= scene.width * scene.height;
    ASSERT_GT(mirrored, 0.2 * direct);  // the caustic is a good part of the image

    const double with = meanOf(render(scene, options(2048)).film);
    EXPECT_NEAR(with, direct + mirrored, 0.03 * (direct + mirrored)) << direct << " " << mirrored;
    scene.caustics = false;
    const double without = meanOf(render(scene, options(64)).film);
    EXPECT_NEAR(without, direct, 0.01 * direct);
}

/// A diffuse floor, a glass ball above it and a small round lamp above that, which the ball
/// focuses onto the floor; with `skyPlane`, under an emissive ceiling plane too; with
/// `sunAndSky`, without the lamp, under an environment map of a blue sky and a small sun.
void glassBallScene(Scene& scene, bool skyPlane = false, bool sunAndSky = false) {
    scene.integrator = "path";
    scene.maxDepth = 6;
    scene.width = scene.height = 20;
    scene.camera = CameraSpec{{0, 2.5, 3.5}, {0, 0.2, 0}, {0, 1, 0}, 40};
    Material floor;
    floor.diffuse = Vec3(0.8);
    Material glass;
    glass.transmission = Vec3(1);
    glass.ior = 1.5;
    Material lamp;
    lamp.emission = Vec3(40);
    const uint32_t fm = scene.addMaterial(floor);
    const uint32_t gm = scene.addMaterial(glass);
    const uint32_t lm = scene.addMaterial(lamp);
    addSquare(scene, 0, 4, true, fm);
    Sphere ball;
    ball.center = Vec3(0, 0.8, 0);
    ball.radius = 0.6;
    scene.primitives.addSphere(ball, gm);
    Sphere bulb;
    bulb.center = Vec3(0.2, 3, -0.2);
    bulb.radius = 0.25;
    if (!sunAndSky) scene.primitives.addSphere(bulb, lm);
    if (sunAndSky) {
        const int w = 64, h = 32;
        std::vector<float> rgb(static_cast<size_t>(w) * h * 3);
        for (size_t i = 0; i < rgb.size(); i += 3) {
            rgb[i] = 0.3f;
            rgb[i + 1] = 0.4f;
            rgb[i + 2] = 0.6f;
        }
        for (int x = 40; x < 42; ++x)  // the sun: 2 x 2 texels 40 degrees up
            for (int y = 10; y < 12; ++y)
                for (int c = 0; c < 3; ++c) rgb[(static_cast<size_t>(y) * w + x) * 3 + c] = 2000;
        scene.environment = std::make_shared<const EnvironmentMap>(w, h, std::move(rgb));
    }
    if (skyPlane) {
        Material sky;
        sky.emission = Vec3(0.5, 0.7, 1.0);
        const std::optional<Plane> ceiling =
            Plane::make({0, 4, 0}, {0, -1, 0}, *Transform::fromMatrix(Mat4()));
        scene.primitives.addPlane(*ceiling, scene.addMaterial(sky));
    }
    scene.prepare();
}

// The light pass and the camera's paths split path space between them: the glass ball's
// caustic traced from the lamp, added to the path tracer's image without those paths, agrees
// with the path tracer's image that has them all, in the mean over the image and over the
// caustic's pixels (where the floor under the ball is brightest).
TEST(CausticPass, TheSplitImageAgreesWithThePathTracerAlone) {
    Scene scene;
    glassBallScene(scene);
    PathIntegrator probe(scene);
    ThreadPool pool(1);
    ASSERT_TRUE(probe.lightPass(0, 1, 1, pool, nullptr)) << "the pass should be on";

    const Film with = render(scene, options(1024)).film;
    scene.caustics = false;
    const Film without = render(scene, options(8192)).film;
    EXPECT_NEAR(meanOf(with), meanOf(without), 0.02 * meanOf(without));
    // The caustic: the floor's pixels that a third render shows brightest.
    RenderOptions pick = options(256);
    pick.seed = 99;
    scene.caustics = true;
    const Film chooser = render(scene, pick).film;
    const auto [a, b] = brightestSums(chooser, with, without, 30);  // not the lamp itself
    EXPECT_GT(a / 16, 2 * meanOf(with)) << "no caustic found";
    EXPECT_NEAR(a, b, 0.06 * b);
}

// Under an emissive plane (a light at infinity that the pass emits from where its lines meet
// the plane), the split image agrees with the path tracer alone too.
TEST(CausticPass, AgreesWithThePathTracerUnderAnEmissivePlane) {
    Scene scene;
    glassBallScene(scene, true);
    const Film with = render(scene, options(256)).film;
    scene.caustics = false;
    const Film without = render(scene, options(1024)).film;
    EXPECT_NEAR(meanOf(with), meanOf(without), 0.02 * meanOf(without));
}

// Under an environment map with a sun: the pass traces the sun (texels far brighter than the
// map's mean), the camera's paths the sky; the split image agrees with the path tracer alone,
// over the image and over the ball's caustic.
TEST(CausticPass, AgreesWithThePathTracerUnderASkyWithASun) {
    Scene scene;
    glassBallScene(scene, false, true);
    RenderOptions pick = options(256);
    pick.seed = 99;
    const Film chooser = render(scene, pick).film;
    const Film with = render(scene, options(512)).film;
    scene.caustics = false;
    const Film without = render(scene, options(4096)).film;
    EXPECT_NEAR(meanOf(with), meanOf(without), 0.02 * meanOf(without));
    const auto [a, b] = brightestSums(chooser, with, without);
    EXPECT_NEAR(a, b, 0.06 * b);
}

// The pass's image does not depend on the thread count, and each range of sample indices is
// the sum of its parts' (up to rounding).
TEST(CausticPass, IsIndependentOfThreadsAndAddsUpOverSampleRanges) {
    Scene scene;
    glassBallScene(scene);
    PathIntegrator integrator(scene);
    ThreadPool one(1), two(2);
    const auto a = integrator.lightPass(0, 3, 11, one, nullptr);
    PathIntegrator other(scene);  // no kept results
    const auto b = other.lightPass(0, 3, 11, two, nullptr);
    ASSERT_TRUE(a && b);
    EXPECT_EQ(a->image, b->image);
    EXPECT_EQ(a->photons.size(), b->photons.size());
    EXPECT_GT(a->photons.size(), 0u);
    const auto first = other.lightPass(0, 1, 11, two, nullptr);
    const auto rest = other.lightPass(1, 3, 11, two, nullptr);
    double total = 0;
    for (size_t i = 0; i < a->image.size(); ++i) {
        const Vec3 sum = first->image[i] + rest->image[i];
        EXPECT_NEAR(sum.x, a->image[i].x, 1e-9 * (1 + std::abs(sum.x)));
        total += a->image[i].x;
    }
    EXPECT_GT(total, 0);
    // A different seed is a different pass.
    const auto c = other.lightPass(0, 3, 12, two, nullptr);
    EXPECT_NE(a->image, c->image);
}

// Nothing to do, and nothing left out of the camera's paths: no caster, or a lens, or off.
TEST(CausticPass, IsOffWithoutCastersOrWithALens) {
    Scene scene;
    glassBallScene(scene);
    scene.materials[1].transmission = Vec3(0);  // the ball turns grey plastic
    scene.materials[1].diffuse = Vec3(0.5);
    ThreadPool pool(1);
    EXPECT_FALSE(PathIntegrator(scene).lightPass(0, 1, 1, pool, nullptr));
    Scene lens;
    glassBallScene(lens);
    lens.camera->apertureRadius = 0.05;
    EXPECT_FALSE(PathIntegrator(lens).lightPass(0, 1, 1, pool, nullptr));
    Scene off;
    glassBallScene(off);
    off.caustics = false;
    EXPECT_FALSE(PathIntegrator(off).lightPass(0, 1, 1, pool, nullptr));
}

}  // namespace
}  // namespace glint
