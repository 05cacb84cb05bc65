// Evaluating glTF's metallic-roughness material at a hit (scene/pbr_material.h): texture
// coordinate sets, KHR_texture_transform, the factor-texture products, normal maps.

#include "glint/scene/pbr_material.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>

#include "unit/test_support.h"

namespace glint {
namespace {

using test::expectNear;

/// A linear 2 x 2 image: top row red, green; bottom row blue, white.
std::shared_ptr<TextureImage> quadrants() {
    auto img = std::make_shared<TextureImage>();
    img->width = img->height = 2;
    img->srgb = false;
    img->rgb = {255, 0, 0, 0, 255, 0, 0, 0, 255, 255, 255, 255};
    return img;
}

SurfaceInteraction at(double u, double v) {
    SurfaceInteraction si;
    si.hasUv = true;
    si.u = u;
    si.v = v;
    si.n = si.ng = {0, 0, 1};
    return si;
}

TEST(TextureSlot, ReadsTheCoordinateSetItNames) {
    TextureSlot s;
    s.image = quadrants();
    s.wrapS = s.wrapT = TextureWrap::Clamp;
    SurfaceInteraction si = at(0.25, 0.75);  // TEXCOORD_0: top left, red
    expectNear(s.sample(si).rgb, {1, 0, 0});
    s.texCoord = 1;
    // No second set: the fallback.
    expectNear(s.sample(si, {Vec3(0.5), 1}).rgb, Vec3(0.5));
    si.hasUv1 = true;
    si.u1 = 0.75;
    si.v1 = 0.25;  // bottom right, white
    expectNear(s.sample(si).rgb, {1, 1, 1});
}

TEST(TextureSlot, TransformsCoordinatesAsKhrTextureTransformDoes) {
    TextureSlot s;
    s.image = quadrants();
    s.wrapS = s.wrapT = TextureWrap::Clamp;
    // glTF coordinates (s, t), t down the image: offset by half a texture to the right moves
    // the top-left texel's lookup (s, t) = (0.25, 0.25) to (0.75, 0.25), the green texel.
    s.setTransform(0.5, 0, 0, 1, 1);
    expectNear(s.sample(at(0.25, 0.75)).rgb, {0, 1, 0});
    // Scale 0.5 maps everything into the top-left quarter: (0.4, 0.4) to (0.2, 0.2), red.
    s.setTransform(0, 0, 0, 0.5, 0.5);
    expectNear(s.sample(at(0.4, 0.6)).rgb, {1, 0, 0});
    // A rotation by 90 degrees: (s, t) -> (t, -s), then offset (0, 1): (0.25, 0.75) in glTF
    // coordinates (bottom left, blue) reads (0.75, 0.75): white.
    s.setTransform(0, 1, std::numbers::pi / 2, 1, 1);
    expectNear(s.sample(at(0.25, 0.25)).rgb, {1, 1, 1}, 1e-9);
}

TEST(PbrMaterial, TexturesMultiplyTheirFactors) {
    PbrMaterial m;
    m.baseColor = {0.5, 0.5, 0.5};
    m.metallic = 0.5;
    m.roughness = 0.8;
    auto mr = std::make_shared<TextureImage>();
    mr->width = mr->height = 1;
    mr->srgb = false;
    mr->rgb = {0, 51, 255};  // roughness 0.2 (green), metalness 1 (blue)
    m.metallicRoughnessTexture.image = mr;
    m.baseColorTexture.image = quadrants();
    m.baseColorTexture.wrapS = m.baseColorTexture.wrapT = TextureWrap::Clamp;
    PbrSurface s = evalSurface(m, at(0.25, 0.25));  // bottom left: blue
    expectNear(s.baseColor, {0, 0, 0.5});
    EXPECT_NEAR(s.metallic, 0.5, 1e-12);
    EXPECT_NEAR(s.roughness, 0.8 * 0.2, 1e-12);
}

TEST(PbrMaterial, ANormalMapBendsTheNormalInTheTangentFrame) {
    PbrMaterial m;
    auto flat = std::make_shared<TextureImage>();
    flat->width = flat->height = 1;
    flat->srgb = false;
    flat->rgb = {128, 128, 255};  // (0, 0, 1), nearly: the unbent normal
    m.normalTexture.image = flat;
    SurfaceInteraction si = at(0.5, 0.5);
    si.hasTangent = true;
    si.tangent = {1, 0, 0};
    expectNear(evalSurface(m, si).normal, {0, 0, 1}, 1e-2);
    // Tilted towards +x (the tangent) by 45 degrees, and towards -y with a bitangent sign of -1.
    auto tilted = std::make_shared<TextureImage>();
    tilted->width = tilted->height = 1;
    tilted->srgb = false;
    tilted->rgb = {218, 128, 218};  // about (0.71, 0, 0.71)
    m.normalTexture.image = tilted;
    Vec3 n = evalSurface(m, si).normal;
    EXPECT_NEAR(n.x, std::sqrt(0.5), 0.01);
    EXPECT_NEAR(n.z, std::sqrt(0.5), 0.01);
    tilted->rgb = {128, 218, 218};  // about (0, 0.71, 0.71): along the bitangent
    si.tangentSign = -1;
    n = evalSurface(m, si).normal;
    EXPECT_NEAR(n.y, -std::sqrt(0.5), 0.01);  // B = -(n x t) = -y
    // The scale multiplies x and y.
    m.normalScale = 0;
    expectNear(evalSurface(m, si).normal, {0, 0, 1}, 1e-12);
    // Without a tangent from the file, dp/du stands in.
    m.normalScale = 1;
    tilted->rgb = {218, 128, 218};
    si.hasTangent = false;
    si.dpdu = {0, 3, 0.1};
    n = evalSurface(m, si).normal;
    EXPECT_NEAR(n.y, std::sqrt(0.5), 0.01);
}

}  // namespace
}  // namespace glint
