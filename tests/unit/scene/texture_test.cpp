#include "glint/scene/texture.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "glint/render/integrators/whitted.h"
#include "unit/test_support.h"

namespace glint {
namespace {

using test::expectNear;

/// A 2 x 2 image, linear (so values are byte / 255): top row red, green; bottom row blue,
/// white.
TextureImage quadImage(bool srgb = false) {
    TextureImage img;
    img.width = 2;
    img.height = 2;
    img.srgb = srgb;
    img.rgb = {255, 0, 0, 0, 255, 0, 0, 0, 255, 255, 255, 255};
    return img;
}

TEST(Texture, SrgbDecodingFollowsTheStandardCurve) {
    EXPECT_EQ(srgbToLinear(0), 0.0);
    EXPECT_EQ(srgbToLinear(255), 1.0);
    EXPECT_NEAR(srgbToLinear(10), 10 / 255.0 / 12.92, 1e-15);  // linear segment
    EXPECT_NEAR(srgbToLinear(128), std::pow((128 / 255.0 + 0.055) / 1.055, 2.4), 1e-15);
    EXPECT_NEAR(srgbToLinear(128), 0.2158605, 1e-6);
    for (int i = 1; i < 256; ++i)
        EXPECT_LT(srgbToLinear(static_cast<uint8_t>(i - 1)), srgbToLinear(static_cast<uint8_t>(i)));
}

TEST(Texture, TexelCentresGiveTheTexelsExactly) {
    TextureImage img = quadImage();
    // Texel (x, y) has its centre at u = (x + 0.5) / 2, v = 1 - (y + 0.5) / 2.
    expectNear(sampleBilinear(img, 0.25, 0.75, TextureWrap::Clamp), {1, 0, 0});
    expectNear(sampleBilinear(img, 0.75, 0.75, TextureWrap::Clamp), {0, 1, 0});
    expectNear(sampleBilinear(img, 0.25, 0.25, TextureWrap::Clamp), {0, 0, 1});
    expectNear(sampleBilinear(img, 0.75, 0.25, TextureWrap::Clamp), {1, 1, 1});
}

TEST(Texture, BilinearFilteringBlendsTheFourNearestTexels) {
    TextureImage img = quadImage();
    // The image's centre is the average of all four texels.
    expectNear(sampleBilinear(img, 0.5, 0.5, TextureWrap::Clamp), {0.5, 0.5, 0.5});
    // Halfway between the two top texels.
    expectNear(sampleBilinear(img, 0.5, 0.75, TextureWrap::Clamp), {0.5, 0.5, 0});
    // A quarter of the way from red to green.
    expectNear(sampleBilinear(img, 0.375, 0.75, TextureWrap::Clamp), {0.75, 0.25, 0});
}

TEST(Texture, ClampStretchesTheEdgeTexels) {
    TextureImage img = quadImage();
    expectNear(sampleBilinear(img, -3, 0.75, TextureWrap::Clamp), {1, 0, 0});
    expectNear(sampleBilinear(img, 0.0, 1.0, TextureWrap::Clamp), {1, 0, 0});
    expectNear(sampleBilinear(img, 7, -2, TextureWrap::Clamp), {1, 1, 1});
}

TEST(Texture, RepeatTilesAndWrapsBetweenOppositeEdges) {
    TextureImage img = quadImage();
    expectNear(sampleBilinear(img, 1.25, 0.75, TextureWrap::Repeat), {1, 0, 0});
    expectNear(sampleBilinear(img, -0.25, -0.25, TextureWrap::Repeat), {0, 1, 0});
    // At u = 0 the left and right columns meet: half red, half green.
    expectNear(sampleBilinear(img, 0.0, 0.75, TextureWrap::Repeat), {0.5, 0.5, 0});
    // Far from the origin, and not finite: still a texel blend, never a crash.
    Vec3 far = sampleBilinear(img, 1e30, -1e30, TextureWrap::Repeat);
    EXPECT_TRUE(isFinite(far));
    double nan = std::numeric_limits<double>::quiet_NaN();
    EXPECT_TRUE(isFinite(sampleBilinear(img, nan, kInfinity, TextureWrap::Repeat)));
    EXPECT_TRUE(isFinite(sampleBilinear(img, nan, -kInfinity, TextureWrap::Clamp)));
}

TEST(Texture, MirroredRepeatReflectsEveryOtherTile) {
    TextureImage img = quadImage();
    // u in [1, 2) mirrors [0, 1): u = 1.25 reads like 0.75 (green column at the top).
    for (double u : {0.25, 0.75})
        for (double k : {0.0, 2.0, -2.0})
            expectNear(sampleBilinear(img, u + k, 0.75, TextureWrap::MirroredRepeat),
                       sampleBilinear(img, u, 0.75, TextureWrap::Clamp));
    expectNear(sampleBilinear(img, 1.25, 0.75, TextureWrap::MirroredRepeat), {0, 1, 0});
    expectNear(sampleBilinear(img, -0.25, 0.75, TextureWrap::MirroredRepeat), {1, 0, 0});
    // At the mirror line the two texels either side are the same texel: no blend with the far
    // edge, unlike repeat.
    expectNear(sampleBilinear(img, 1.0, 0.75, TextureWrap::MirroredRepeat), {0, 1, 0});
    expectNear(sampleBilinear(img, 1.0, 0.75, TextureWrap::Repeat), {0.5, 0.5, 0});
}

TEST(Texture, EachAxisWrapsItsOwnWayAndAlphaIsFiltered) {
    TextureImage img = quadImage();
    img.alpha = {255, 0, 255, 0};  // the left column opaque, the right transparent
    // u repeats, v clamps: u = 1.25 is the left column, v = 1.5 the top row.
    Rgba r = sampleBilinearRgba(img, 1.25, 1.5, TextureWrap::Repeat, TextureWrap::Clamp);
    expectNear(r.rgb, {1, 0, 0});
    EXPECT_NEAR(r.a, 1, 1e-12);
    Rgba mid = sampleBilinearRgba(img, 0.5, 0.75, TextureWrap::Clamp, TextureWrap::Clamp);
    EXPECT_NEAR(mid.a, 0.5, 1e-12);
    EXPECT_NEAR(sampleBilinearRgba(img, 0.75, 0.25, TextureWrap::Clamp, TextureWrap::Clamp).a, 0,
                1e-12);
}

TEST(Texture, SrgbImagesAreDecodedBeforeFiltering) {
    TextureImage img;
    img.width = 2;
    img.height = 1;
    img.rgb = {0, 0, 0, 128, 128, 128};
    // Halfway: the mean of the decoded values, not the decoded mean of the bytes.
    expectNear(sampleBilinear(img, 0.5, 0.5, TextureWrap::Clamp), Vec3(srgbToLinear(128) / 2));
    expectNear(img.average(), Vec3(srgbToLinear(128) / 2));
}

TEST(Texture, CheckerParityIsExactEvenFarAway) {
    EXPECT_EQ(checkerParity(0.5, 1), 0);
    EXPECT_EQ(checkerParity(1.5, 1), 1);
    EXPECT_EQ(checkerParity(-0.5, 1), 1);
    EXPECT_EQ(checkerParity(-1.5, 1), 0);
    EXPECT_EQ(checkerParity(0.3, 0.25), 1);
    EXPECT_EQ(checkerParity(1e300, 1), 0);  // an even whole number
    EXPECT_EQ(checkerParity(std::numeric_limits<double>::quiet_NaN(), 1), 0);
}

TEST(Texture, CheckerUsesUvWhenPresentElseWorldCellsCentredOnWholeMultiples) {
    Texture t;
    t.kind = Texture::Kind::Checker;
    t.a = {1, 0, 0};
    t.b = {0, 0, 1};
    t.scale = 0.5;
    Vec3 anywhere(100.3, -7, 2);
    expectNear(t.eval(true, 0.25, 0.25, anywhere, {}), {1, 0, 0});
    expectNear(t.eval(true, 0.75, 0.25, anywhere, {}), {0, 0, 1});
    expectNear(t.eval(true, 0.75, 0.75, anywhere, {}), {1, 0, 0});
    // Without uv: cells of side 0.5 with boundaries at odd multiples of 0.25, so the floor
    // y = 0 lies mid-cell and the origin is in an `a` cell.
    expectNear(t.eval(false, 0, 0, {0, 0, 0}, {}), {1, 0, 0});
    expectNear(t.eval(false, 0, 0, {0.3, 0, 0}, {}), {0, 0, 1});
    expectNear(t.eval(false, 0, 0, {0.3, 0, 0.3}, {}), {1, 0, 0});
    expectNear(t.eval(false, 0, 0, {0.2, 1e-12, -1e-12}, {}), {1, 0, 0});
}

TEST(Texture, ImageTexturesNeedUvAndAreTinted) {
    Texture t;
    t.kind = Texture::Kind::Image;
    t.wrap = TextureWrap::Clamp;
    t.image = std::make_shared<TextureImage>(quadImage());
    t.a = {0.5, 0.5, 0.5};
    expectNear(t.eval(true, 0.25, 0.75, {}, {9, 9, 9}), {0.5, 0, 0});
    expectNear(t.eval(false, 0.25, 0.75, {}, {9, 9, 9}), {9, 9, 9});
}

// ---- Shading with a texture ----

/// A floor z = 0 of two triangles over [-1, 1]^2 with uv = (x + 1) / 2, (y + 1) / 2.
void addTexturedFloor(Scene& scene, uint32_t material) {
    Vec3 p[4] = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
    TexCoord uv[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    const TexCoord t1[3] = {uv[0], uv[1], uv[2]}, t2[3] = {uv[0], uv[2], uv[3]};
    scene.primitives.addTriangle(p[0], p[1], p[2], nullptr, t1, material);
    scene.primitives.addTriangle(p[0], p[2], p[3], nullptr, t2, material);
}

Vec3 shadeFromAbove(Scene& scene, double x, double y) {
    if (!scene.prepared()) scene.prepare();
    RayCounts counts;
    return WhittedIntegrator(scene).radiance(Ray{{x, y, 5}, {0, 0, -1}}, 0, counts);
}

TEST(TexturedShading, TheTextureReplacesTheDiffuseColour) {
    Scene scene;
    Texture t;
    t.kind = Texture::Kind::Image;
    t.wrap = TextureWrap::Clamp;
    t.image = std::make_shared<TextureImage>(quadImage());
    Material m = test::makeMaterial({0, 0, 0}, {0.2, 0.2, 0.2});
    m.texture = scene.addTexture(t);
    addTexturedFloor(scene, scene.addMaterial(m));
    LightSpec l;
    l.kind = LightSpec::Kind::Directional;
    l.direction = {0, 0, 1};
    l.color = {1, 1, 1};
    scene.lights.push_back(l);
    // uv (0.25, 0.75) is the centre of the top-left (red) texel, at x = -0.5, y = 0.5.
    expectNear(shadeFromAbove(scene, -0.5, 0.5), {1, 0, 0});
    expectNear(shadeFromAbove(scene, 0.5, -0.5), {1, 1, 1});
    expectNear(shadeFromAbove(scene, 0, 0), {0.5, 0.5, 0.5});
}

TEST(TexturedShading, UntexturedTrianglesBesideTexturedOnesKeepTheirColour) {
    Scene scene;
    Texture t;  // checker over uv: a 2 x 2 board on the floor
    t.a = {1, 1, 1};
    t.b = {0, 0, 0};
    t.scale = 0.5;
    Material m = test::makeMaterial({0, 0, 0}, {0.3, 0.3, 0.3});
    m.texture = scene.addTexture(t);
    uint32_t textured = scene.addMaterial(m);
    uint32_t plain = scene.addMaterial(test::makeMaterial({0, 0, 0}, {0, 0.7, 0}));
    // A plain triangle added first, before any triangle had coordinates, and one after.
    scene.primitives.addTriangle({2, 2, 0}, {4, 2, 0}, {2, 4, 0}, nullptr, plain);
    addTexturedFloor(scene, textured);
    scene.primitives.addTriangle({-4, -4, 0}, {-2, -4, 0}, {-4, -2, 0}, nullptr, plain);
    LightSpec l;
    l.kind = LightSpec::Kind::Directional;
    l.direction = {0, 0, 1};
    l.color = {1, 1, 1};
    scene.lights.push_back(l);
    expectNear(shadeFromAbove(scene, -0.5, -0.5), {1, 1, 1});
    expectNear(shadeFromAbove(scene, 0.5, -0.5), {0, 0, 0});
    expectNear(shadeFromAbove(scene, 2.5, 2.5), {0, 0.7, 0});
    expectNear(shadeFromAbove(scene, -3.5, -3.5), {0, 0.7, 0});
    EXPECT_EQ(scene.primitives.texturedTriangleCount(), 2u);
}

}  // namespace
}  // namespace glint
