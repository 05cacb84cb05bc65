// RenderOptions::cropFilm: a crop rendered into a film of the crop's size holds the whole
// render's pixels bit for bit, shifted to the crop's corner; also with one integrator shared by
// many such renders (RenderOptions::integrator). The MPI mode renders its tiles so.

#include <gtest/gtest.h>

#include <algorithm>

#include "glint/render/renderer.h"
#include "unit/test_support.h"

namespace glint {
namespace {

/// A red sphere on a grey floor under a point light, path traced through a thin lens, on an
/// image whose sides are no multiple of the tile size.
void buildScene(Scene& scene) {
    scene.width = 27;
    scene.height = 19;
    scene.maxDepth = 3;
    scene.integrator = "path";
    CameraSpec camera{{0, 2, 6}, {0, 0.7, 0}, {0, 1, 0}, 45};
    camera.apertureRadius = 0.05;
    scene.camera = camera;
    uint32_t floor = scene.addMaterial(test::makeMaterial({0.02, 0.02, 0.02}, {0.5, 0.5, 0.5}));
    scene.primitives.addTriangle({-5, 0, -5}, {-5, 0, 5}, {5, 0, 5}, nullptr, floor);
    scene.primitives.addTriangle({-5, 0, -5}, {5, 0, 5}, {5, 0, -5}, nullptr, floor);
    uint32_t red = scene.addMaterial(test::makeMaterial({0, 0, 0}, {0.8, 0.1, 0.1}));
    scene.primitives.addSphere(Sphere{{0, 1, 0}, 1, {}}, red);
    LightSpec point;
    point.position = {3, 5, 3};
    point.color = {8, 8, 8};
    scene.lights.push_back(point);
    scene.prepare();
}

RenderOptions options() {
    RenderOptions o;
    o.threads = 2;
    o.tileSize = 8;
    o.spp = 5;
    o.seed = 3;
    return o;
}

TEST(CropFilm, HoldsTheCropsPixelsOfTheWholeRenderBitForBit) {
    Scene scene;
    buildScene(scene);
    const RenderResult whole = render(scene, options());
    // Off the tile grid, one reaching the image's corner, one a single pixel, one past the
    // image's edge (clipped to it).
    for (const PixelBounds& c : {PixelBounds{3, 17, 5, 12}, PixelBounds{20, 27, 11, 19},
                                 PixelBounds{9, 10, 4, 5}, PixelBounds{24, 40, 0, 3}}) {
        RenderOptions o = options();
        o.crop = c;
        o.cropFilm = true;
        o.keepSums = true;
        const RenderResult part = render(scene, o);
        const int x1 = std::min(c.x1, scene.width), y1 = std::min(c.y1, scene.height);
        ASSERT_EQ(part.film.width(), x1 - c.x0);
        ASSERT_EQ(part.film.height(), y1 - c.y0);
        ASSERT_EQ(part.sums.width(), x1 - c.x0);
        int differ = 0;
        for (int y = c.y0; y < y1; ++y)
            for (int x = c.x0; x < x1; ++x) {
                differ += !(part.film.at(x - c.x0, y - c.y0) == whole.film.at(x, y));
                EXPECT_EQ(part.sums.weight(x - c.x0, y - c.y0), 5);
            }
        EXPECT_EQ(differ, 0) << "pixels that differ in crop " << c.x0 << "," << c.x1 << "," << c.y0
                             << "," << c.y1;
    }
}

TEST(CropFilm, WithoutACropTheFilmIsTheWholeImage) {
    Scene scene;
    buildScene(scene);
    RenderOptions o = options();
    o.cropFilm = true;
    const RenderResult r = render(scene, o);
    EXPECT_EQ(r.film.width(), scene.width);
    EXPECT_EQ(r.film.height(), scene.height);
    const RenderResult whole = render(scene, options());
    EXPECT_TRUE(r.film.at(13, 9) == whole.film.at(13, 9));
}

TEST(CropFilm, TilesSharingOneIntegratorGiveTheSamePixels) {
    Scene scene;
    buildScene(scene);
    const RenderResult whole = render(scene, options());
    const std::unique_ptr<Integrator> integrator = makeIntegrator(scene, {options().spp});
    RenderOptions o = options();
    o.integrator = integrator.get();
    o.cropFilm = true;
    int differ = 0;
    for (int y0 = 0; y0 < scene.height; y0 += 8)
        for (int x0 = 0; x0 < scene.width; x0 += 8) {
            o.crop = {x0, std::min(x0 + 8, scene.width), y0, std::min(y0 + 8, scene.height)};
            const RenderResult tile = render(scene, o);
            for (int y = o.crop.y0; y < o.crop.y1; ++y)
                for (int x = o.crop.x0; x < o.crop.x1; ++x)
                    differ += !(tile.film.at(x - x0, y - y0) == whole.film.at(x, y));
        }
    EXPECT_EQ(differ, 0);
}

}  // namespace
}  // namespace glint
