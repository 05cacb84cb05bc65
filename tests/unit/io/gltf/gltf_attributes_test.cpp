// glTF's further vertex attributes (io/gltf/gltf_meshes.cpp): TEXCOORD_1, COLOR_0 and TANGENT
// read into MeshData's per-corner indices, their checks, and tangents generated for primitives
// whose material has a normal map but that have no TANGENT. Assets are written by the tests.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <limits>
#include <string>

#include "glint/io/gltf/gltf_loader.h"
#include "unit/io/gltf/gltf_asset_builder.h"
#include "unit/io/gltf/gltf_test_support.h"
#include "unit/test_support.h"

namespace glint {
namespace {

using namespace glint::test;
using ::testing::HasSubstr;

/// The unit square in z = 0 facing +z, indexed as two triangles, with glTF's texture
/// coordinates (v down the image: (0, 0) at the top left, which is position (0, 1)), and
/// normals; `attributes` adds to its primitive's attributes, `primitive` to the primitive.
struct Square {
    GltfAsset asset;
    int position, normal, uv, indices;

    Square() {
        position = asset.floats({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0}, "VEC3");
        normal = asset.floats({0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3");
        uv = asset.floats({0, 1, 1, 1, 1, 0, 0, 0}, "VEC2");
        indices = asset.integers({0, 1, 2, 0, 2, 3}, GltfAsset::kUshort, "SCALAR");
    }
    std::string text(const std::string& attributes, const std::string& primitive = "",
                     const std::string& more = "") const {
        return asset.text(R"("meshes": [{"primitives": [{"attributes": {"POSITION": )" +
                          std::to_string(position) + R"(, "NORMAL": )" + std::to_string(normal) +
                          R"(, "TEXCOORD_0": )" + std::to_string(uv) + attributes +
                          R"(}, "indices": )" + std::to_string(indices) + primitive +
                          R"(}]}], "nodes": [{"mesh": 0}])" + more);
    }
};

std::string attr(const char* name, int accessor) {
    return std::string(", \"") + name + "\": " + std::to_string(accessor);
}

const MeshData::Corner& corner(const MeshData& m, size_t t, size_t k) {
    return m.triangles[t].corners[k];
}

TEST(GltfAttributes, SecondTextureCoordinatesAreTurnedAsTheFirst) {
    Square s;
    int uv1 = s.asset.floats({0, 0.25f, 0.5f, 0.25f, 0.5f, 0.75f, 0, 0.75f}, "VEC2");
    Model model = parse(s.text(attr("TEXCOORD_1", uv1)));
    const MeshData& m = model.meshes[0];
    ASSERT_EQ(m.uv1s.size(), 4u);
    // Vertex 2 (position (1, 1)): glTF (0.5, 0.75) is Glint's (0.5, 0.25), v turned up.
    const MeshData::Corner& c = corner(m, 0, 2);
    ASSERT_NE(c.uv1, MeshData::kNone);
    EXPECT_EQ(m.uv1s[c.uv1][0], 0.5f);
    EXPECT_EQ(m.uv1s[c.uv1][1], 0.25f);
    EXPECT_EQ(m.uvs[c.uv][1], 1.0f);  // the first set, for comparison: glTF's 0
    for (size_t t = 0; t < 2; ++t)
        for (size_t k = 0; k < 3; ++k) EXPECT_NE(corner(m, t, k).uv1, MeshData::kNone);
}

TEST(GltfAttributes, VertexColoursAreLinearRgbaWithAlphaOneForVec3) {
    Square s;
    int rgb = s.asset.floats({1, 0, 0, 0, 1, 0, 0, 0, 1, 0.5f, 0.5f, 0.5f}, "VEC3");
    Model model = parse(s.text(attr("COLOR_0", rgb)));
    const MeshData& m = model.meshes[0];
    ASSERT_EQ(m.colors.size(), 4u);
    const auto& c2 = m.colors[corner(m, 0, 2).color];  // vertex 2: blue
    EXPECT_EQ(c2, (std::array<float, 4>{0, 0, 1, 1}));
    const auto& c3 = m.colors[corner(m, 1, 2).color];  // vertex 3: grey, as given (linear)
    EXPECT_EQ(c3, (std::array<float, 4>{0.5f, 0.5f, 0.5f, 1}));

    // Normalised unsigned bytes and shorts, VEC4: x / 255 and x / 65535, alpha kept.
    Square b;
    int bytes = b.asset.integers({255, 0, 0, 51, 0, 255, 0, 255, 0, 0, 255, 255, 0, 0, 0, 0},
                                 GltfAsset::kUbyte, "VEC4", true);
    model = parse(b.text(attr("COLOR_0", bytes)));
    const auto& c0 = model.meshes[0].colors[corner(model.meshes[0], 0, 0).color];
    EXPECT_FLOAT_EQ(c0[0], 1);
    EXPECT_FLOAT_EQ(c0[3], 0.2f);
    Square h;
    int shorts = h.asset.integers({65535, 32768, 0, 65535, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0},
                                  GltfAsset::kUshort, "VEC4", true);
    model = parse(h.text(attr("COLOR_0", shorts)));
    const auto& s0 = model.meshes[0].colors[corner(model.meshes[0], 0, 0).color];
    EXPECT_FLOAT_EQ(s0[1], 32768.0f / 65535);
    EXPECT_FLOAT_EQ(s0[3], 1);
}

TEST(GltfAttributes, ColoursAreCheckedAsTheOtherAttributes) {
    Square s;
    int scalar = s.asset.floats({1, 1, 1, 1}, "SCALAR");
    EXPECT_EQ(errorParsing(s.text(attr("COLOR_0", scalar))).message,
              "accessor 4 (COLOR_0 of mesh 0, primitive 0): its elements are SCALAR, not VEC3 "
              "or VEC4");
    Square b;
    int plain = b.asset.integers({1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1}, GltfAsset::kUbyte, "VEC3");
    EXPECT_EQ(errorParsing(b.text(attr("COLOR_0", plain))).message,
              "accessor 4 (COLOR_0 of mesh 0, primitive 0): its components must be floats, or "
              "normalised unsigned bytes or shorts");
    Square c;
    int three = c.asset.floats({1, 1, 1, 1, 1, 1, 1, 1, 1}, "VEC3");
    EXPECT_EQ(errorParsing(c.text(attr("COLOR_0", three))).message,
              "accessor 4 (COLOR_0 of mesh 0, primitive 0): it has 3 elements, but POSITION "
              "has 4");
    Square n;
    int nan = n.asset.floats(
        {1, 1, 1, 1, 1, 1, 1, 1, 1, 0, std::numeric_limits<float>::infinity(), 0}, "VEC3");
    EXPECT_THAT(errorParsing(n.text(attr("COLOR_0", nan))).message,
                HasSubstr("element 3 is not a finite colour"));
}

TEST(GltfAttributes, TangentsFromTheFileAreKeptNormalisedWithTheirSign) {
    Square s;
    int tangents = s.asset.floats({2, 0, 0, 1, 2, 0, 0, 1, 0, 3, 0, -1, 0, 3, 0, -1}, "VEC4");
    Model model = parse(s.text(attr("TANGENT", tangents)));
    const MeshData& m = model.meshes[0];
    ASSERT_EQ(m.tangents.size(), 4u);
    EXPECT_EQ(m.tangents[corner(m, 0, 0).tangent], (std::array<float, 4>{1, 0, 0, 1}));
    EXPECT_EQ(m.tangents[corner(m, 0, 2).tangent], (std::array<float, 4>{0, 1, 0, -1}));
    Square v;
    int vec3 = v.asset.floats({1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0}, "VEC3");
    EXPECT_EQ(errorParsing(v.text(attr("TANGENT", vec3))).message,
              "accessor 4 (TANGENT of mesh 0, primitive 0): its elements are VEC3, not VEC4");
}

/// A material with a normal map on texture coordinates `set`; its image need not exist (the
/// warning about it is not what these tests look at).
std::string normalMapped(int set) {
    return R"("materials": [{"normalTexture": {"index": 0, "texCoord": )" + std::to_string(set) +
           R"(}}], "textures": [{"source": 0}], "images": [{"uri": "normal.png"}])";
}

TEST(GltfAttributes, ANormalMappedPrimitiveWithoutTangentsGetsMikkTSpaceTangents) {
    Square s;
    std::vector<Diagnostic> warnings;
    GltfOptions noFiles;
    noFiles.limits.readFiles = false;
    Model model =
        parse(s.text("", R"(, "material": 0)", ", " + normalMapped(0)), &warnings, noFiles);
    const MeshData& m = model.meshes[0];
    // One tangent per vertex: u runs along +x, and glTF's v down the image is Glint's v up it,
    // so the bitangent N x T = +y points up the image: sign +1.
    ASSERT_EQ(m.tangents.size(), 4u);
    for (size_t t = 0; t < 2; ++t)
        for (size_t k = 0; k < 3; ++k) {
            const auto& tg = m.tangents[corner(m, t, k).tangent];
            expectNear({tg[0], tg[1], tg[2]}, {1, 0, 0}, 1e-7);
            EXPECT_EQ(tg[3], 1);
        }
}

TEST(GltfAttributes, TangentsFollowTheNormalMapsTextureCoordinates) {
    Square s;
    // TEXCOORD_1 with u and v swapped: Glint's u runs up the square and v along it (glTF's
    // v = 1 - Glint's), a mirrored layout.
    int uv1 = s.asset.floats({0, 1, 0, 0, 1, 0, 1, 1}, "VEC2");
    std::vector<Diagnostic> warnings;
    GltfOptions noFiles;
    noFiles.limits.readFiles = false;
    Model model =
        parse(s.text(attr("TEXCOORD_1", uv1), R"(, "material": 0)", ", " + normalMapped(1)),
              &warnings, noFiles);
    const MeshData& m = model.meshes[0];
    ASSERT_FALSE(m.tangents.empty());
    const auto& tg = m.tangents[corner(m, 0, 0).tangent];
    expectNear({tg[0], tg[1], tg[2]}, {0, 1, 0}, 1e-7);
    EXPECT_EQ(tg[3], -1);  // N x T = -x, but dp/dv = +x
}

TEST(GltfAttributes, NoTangentsAreGeneratedWithoutANormalMapOrWhenTheFileHasThem) {
    Square s;
    Model model =
        parse(s.text("", R"(, "material": 0)", R"(, "materials": [{"pbrMetallicRoughness": {}}])"));
    EXPECT_TRUE(model.meshes[0].tangents.empty());
    EXPECT_EQ(corner(model.meshes[0], 0, 0).tangent, MeshData::kNone);
    Square f;
    int tangents = f.asset.floats({0, 1, 0, -1, 0, 1, 0, -1, 0, 1, 0, -1, 0, 1, 0, -1}, "VEC4");
    std::vector<Diagnostic> warnings;
    GltfOptions noFiles;
    noFiles.limits.readFiles = false;
    model = parse(f.text(attr("TANGENT", tangents), R"(, "material": 0)", ", " + normalMapped(0)),
                  &warnings, noFiles);
    ASSERT_EQ(model.meshes[0].tangents.size(), 4u);  // the file's, not generated ones
    EXPECT_EQ(model.meshes[0].tangents[0], (std::array<float, 4>{0, 1, 0, -1}));
}

TEST(GltfAttributes, GeneratedTangentsMatchBlendersMikkTSpace) {
    // Blender 3.4's Suzanne (smooth, triangulated, its uv layout mirrored on the left half),
    // exported with the tangents Blender's MikkTSpace computes (make_blender_monkey.py); read
    // as it is, and without its TANGENT attribute, so that Glint generates them: every corner
    // gets Blender's tangent (to float precision) and sign.
    std::ifstream in(dataPath("blender-monkey.gltf"));
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::string attribute = R"("TANGENT" : 3)";
    const size_t at = text.find(attribute);
    ASSERT_NE(at, std::string::npos);
    std::string without = text;
    const size_t comma = without.rfind(',', at);
    without.erase(comma, at + attribute.size() - comma);
    Model blender = parse(text), glint = parse(without);
    const MeshData &a = blender.meshes[0], &b = glint.meshes[0];
    ASSERT_EQ(a.triangles.size(), b.triangles.size());
    ASSERT_FALSE(b.tangents.empty());
    size_t corners = 0, close = 0, mirrored = 0;
    double worst = 1;
    for (size_t t = 0; t < a.triangles.size(); ++t)
        for (size_t k = 0; k < 3; ++k) {
            const auto& ta = a.tangents[corner(a, t, k).tangent];
            const auto& tb = b.tangents[corner(b, t, k).tangent];
            const double d = dot(Vec3(ta[0], ta[1], ta[2]), Vec3(tb[0], tb[1], tb[2]));
            EXPECT_EQ(ta[3], tb[3]) << "triangle " << t << " corner " << k;
            worst = std::min(worst, d);
            close += d > 0.99999;  // within 0.26 degrees
            mirrored += ta[3] < 0;
            ++corners;
        }
    EXPECT_GT(mirrored, corners / 4);  // its left half is mirrored
    EXPECT_EQ(close, corners) << "worst cosine " << worst;
}

TEST(GltfAttributes, ExtrasReachTheScene) {
    Square s;
    int rgba = s.asset.floats({1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1}, "VEC4");
    Model model = parse(s.text(attr("COLOR_0", rgba)));
    SceneBuilder builder;
    placeModel(builder, model, Transform(), builder.addMaterial(Material{}));
    auto scene = builder.finish();
    scene->prepare();
    auto si = shoot(*scene, {0.3, 0.6, 1}, {0, 0, -1});
    ASSERT_TRUE(si);
    EXPECT_TRUE(si->hasColor);
    expectNear(si->color, {1, 0, 0}, 1e-6);
}

}  // namespace
}  // namespace glint
