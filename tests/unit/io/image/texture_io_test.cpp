// Texture images (io/image/texture_io.h): WebP through libwebp beside the formats stb_image
// reads, their sizes checked before decoding, damaged files a clear error.

#include "glint/io/image/texture_io.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <string>

#include "glint/core/error.h"

namespace glint {
namespace {

using ::testing::HasSubstr;

std::string bytesOf(const std::string& name) {
    std::ifstream in(std::string(GLINT_TEST_DATA_DIR) + "/gltf/" + name, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::string errorOf(const std::string& bytes) {
    try {
        decodeTextureImage(bytes, "t.webp");
    } catch (const RenderError& e) {
        return e.what();
    }
    ADD_FAILURE() << "no error";
    return "";
}

TEST(TextureIo, DecodesALosslessWebpWithItsAlphaExactly) {
    if (!decodesWebp()) GTEST_SKIP() << "this build decodes no WebP";
    // 4 x 2: red, green, blue, white / black, grey, yellow at alpha 128, clear (make_webp.c).
    auto t = decodeTextureImage(bytesOf("quadrants_alpha.webp"), "q.webp", false);
    ASSERT_EQ(t->width, 4);
    ASSERT_EQ(t->height, 2);
    EXPECT_EQ(t->texel(0, 0), Vec3(1, 0, 0));
    EXPECT_EQ(t->texel(1, 0), Vec3(0, 1, 0));
    EXPECT_EQ(t->texel(2, 0), Vec3(0, 0, 1));
    EXPECT_EQ(t->texel(1, 1), Vec3(128 / 255.0));
    ASSERT_EQ(t->alpha.size(), 8u);
    EXPECT_EQ(t->alphaTexel(0, 0), 1.0);
    EXPECT_NEAR(t->alphaTexel(2, 1), 128 / 255.0, 1e-12);
    EXPECT_EQ(t->alphaTexel(3, 1), 0.0);
    EXPECT_EQ(t->name, "q.webp");
}

TEST(TextureIo, DecodesALossyOpaqueWebpWithoutAlpha) {
    if (!decodesWebp()) GTEST_SKIP() << "this build decodes no WebP";
    // 16 x 16: red rises to the right, green downwards, blue 128 (lossy, quality 90).
    auto t = decodeTextureImage(bytesOf("gradient.webp"), "g.webp", false);
    ASSERT_EQ(t->width, 16);
    ASSERT_EQ(t->height, 16);
    EXPECT_TRUE(t->alpha.empty());
    EXPECT_LT(t->texel(0, 8).x, 0.1);
    EXPECT_GT(t->texel(15, 8).x, 0.8);
    EXPECT_LT(t->texel(8, 0).y, 0.1);
    EXPECT_GT(t->texel(8, 15).y, 0.8);
    EXPECT_NEAR(t->texel(8, 8).z, 128 / 255.0, 0.05);
}

TEST(TextureIo, ADamagedWebpIsAClearError) {
    const std::string good = bytesOf("quadrants_alpha.webp");
    ASSERT_GT(good.size(), 30u);
    std::string damaged = good;
    for (size_t i = 20; i < damaged.size(); ++i) damaged[i] = static_cast<char>(0xff);
    const std::string expected = decodesWebp() ? "t.webp" : "does not decode WebP";
    EXPECT_THAT(errorOf(damaged), HasSubstr(expected));
    EXPECT_THAT(errorOf(good.substr(0, 24)), HasSubstr("cannot read texture 't.webp'"));
    if (decodesWebp()) {
        EXPECT_THAT(errorOf(good.substr(0, 24)), HasSubstr("WebP"));
    }
}

}  // namespace
}  // namespace glint
