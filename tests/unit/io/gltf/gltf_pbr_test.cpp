// glTF materials as physically based materials (scene/pbr_material.h): every texture slot with
// its sampler, coordinate set and KHR_texture_transform, alpha modes, sidedness, emission
// strength, transmission, index of refraction and volume.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "unit/io/gltf/gltf_test_support.h"

namespace glint::test {
namespace {

using testing::HasSubstr;

/// The PbrMaterial of the triangle's material `material` (JSON of one glTF material), with
/// `extra` top-level members (images, textures, samplers) and textures read from
/// tests/data/gltf.
PbrMaterial pbrOf(const std::string& material, const std::string& extra = "",
                  std::vector<Diagnostic>* warnings = nullptr) {
    std::string text = gltfText(kTriangleScene + (extra.empty() ? "" : ", " + extra) +
                                    R"(, "materials": [)" + material + "]",
                                kTriangle);
    text.replace(text.find(R"({"POSITION": 0})"), 15, R"({"POSITION": 0}, "material": 0)");
    std::vector<Diagnostic> w;
    Model model = parseGltf(text, dataPath("t.gltf"), w, {});
    if (warnings)
        *warnings = w;
    else
        EXPECT_TRUE(w.empty()) << w.front().format("warning");
    EXPECT_EQ(model.meshes.size(), 1u);
    EXPECT_EQ(model.meshes[0].materials.size(), 1u);
    EXPECT_TRUE(model.meshes[0].materials[0].pbr.has_value());
    return *model.meshes[0].materials[0].pbr;
}

const std::string kImage = R"("images": [{"uri": "quadrants.png"}])";

TEST(GltfPbr, LayerExtensionsAreReadWithTheirDefaults) {
    PbrMaterial p = pbrOf(R"({"extensions": {
            "KHR_materials_clearcoat": {"clearcoatFactor": 0.9, "clearcoatRoughnessFactor": 0.2,
                "clearcoatNormalTexture": {"index": 0, "scale": 0.5},
                "clearcoatTexture": {"index": 0}},
            "KHR_materials_sheen": {"sheenColorFactor": [0.9, 0.5, 0.1],
                "sheenRoughnessFactor": 0.3, "sheenColorTexture": {"index": 0}},
            "KHR_materials_specular": {"specularFactor": 0.4,
                "specularColorFactor": [2, 1, 0.5]},
            "KHR_materials_anisotropy": {"anisotropyStrength": 0.6, "anisotropyRotation": 1.5},
            "KHR_materials_iridescence": {"iridescenceFactor": 1, "iridescenceIor": 1.8,
                "iridescenceThicknessMaximum": 800, "iridescenceThicknessTexture": {"index": 0}},
            "KHR_materials_diffuse_transmission": {"diffuseTransmissionFactor": 0.25,
                "diffuseTransmissionColorFactor": [0.5, 1, 0]}}})",
                          kImage + R"(, "textures": [{"source": 0}])");
    EXPECT_EQ(p.clearcoat, 0.9);
    EXPECT_EQ(p.clearcoatRoughness, 0.2);
    ASSERT_TRUE(p.clearcoatNormalTexture);
    EXPECT_FALSE(p.clearcoatNormalTexture.image->srgb);
    EXPECT_EQ(p.clearcoatNormalScale, 0.5);
    EXPECT_TRUE(p.clearcoatTexture);
    EXPECT_EQ(p.sheenColor, Vec3(0.9, 0.5, 0.1));
    EXPECT_EQ(p.sheenRoughness, 0.3);
    ASSERT_TRUE(p.sheenColorTexture);
    EXPECT_TRUE(p.sheenColorTexture.image->srgb);  // a colour
    EXPECT_EQ(p.specular, 0.4);
    EXPECT_EQ(p.specularColor, Vec3(2, 1, 0.5));  // the specification allows colours above 1
    EXPECT_EQ(p.anisotropy, 0.6);
    EXPECT_EQ(p.anisotropyRotation, 1.5);
    EXPECT_EQ(p.iridescence, 1);
    EXPECT_EQ(p.iridescenceIor, 1.8);
    EXPECT_EQ(p.iridescenceThicknessMin, 100);  // the default
    EXPECT_EQ(p.iridescenceThicknessMax, 800);
    EXPECT_TRUE(p.iridescenceThicknessTexture);
    EXPECT_EQ(p.diffuseTransmission, 0.25);
    EXPECT_EQ(p.diffuseTransmissionColor, Vec3(0.5, 1, 0));
    // Absent extensions leave the base alone: no coat, no sheen, the index's f0 as it is.
    PbrMaterial plain = pbrOf(R"({"pbrMetallicRoughness": {}})");
    EXPECT_EQ(plain.clearcoat, 0);
    EXPECT_EQ(plain.sheenColor, Vec3(0));
    EXPECT_EQ(plain.specular, 1);
    EXPECT_EQ(plain.specularColor, Vec3(1));
    EXPECT_EQ(plain.iridescence, 0);
    EXPECT_EQ(plain.diffuseTransmission, 0);
}

TEST(GltfPbr, LayerExtensionsWithBadNumbersAreErrors) {
    std::vector<Diagnostic> w;
    std::string text = gltfText(kTriangleScene + R"(, "materials": [{"extensions": {
        "KHR_materials_sheen": {"sheenColorFactor": [1, "red", 0]}}}])",
                                kTriangle);
    text.replace(text.find(R"({"POSITION": 0})"), 15, R"({"POSITION": 0}, "material": 0)");
    try {
        parseGltf(text, dataPath("t.gltf"), w, {});
        ADD_FAILURE() << "no error";
    } catch (const SceneError& e) {
        EXPECT_THAT(e.diagnostic().message, HasSubstr("sheenColorFactor must be finite numbers"));
    }
}

TEST(GltfPbr, FactorsAndTexturesOfEverySlotAreKept) {
    PbrMaterial p = pbrOf(R"({"pbrMetallicRoughness": {
            "baseColorFactor": [0.5, 0.25, 1, 0.75], "metallicFactor": 0.3,
            "roughnessFactor": 0.6, "baseColorTexture": {"index": 0},
            "metallicRoughnessTexture": {"index": 1}},
          "normalTexture": {"index": 1, "scale": 0.5},
          "emissiveTexture": {"index": 0}, "emissiveFactor": [1, 0.5, 0],
          "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 4}},
          "alphaMode": "MASK", "alphaCutoff": 0.3, "doubleSided": true})",
                          kImage + R"(, "textures": [{"source": 0}, {"source": 0}])");
    EXPECT_EQ(p.baseColor, Vec3(0.5, 0.25, 1));
    EXPECT_EQ(p.alpha, 0.75);
    EXPECT_EQ(p.metallic, 0.3);
    EXPECT_EQ(p.roughness, 0.6);
    ASSERT_TRUE(p.baseColorTexture);
    EXPECT_TRUE(p.baseColorTexture.image->srgb);  // colours are sRGB-encoded
    ASSERT_TRUE(p.metallicRoughnessTexture);
    EXPECT_FALSE(p.metallicRoughnessTexture.image->srgb);  // data is linear
    ASSERT_TRUE(p.normalTexture);
    EXPECT_FALSE(p.normalTexture.image->srgb);
    EXPECT_EQ(p.normalScale, 0.5);
    EXPECT_EQ(p.emissive, Vec3(4, 2, 0));
    EXPECT_TRUE(p.emissiveTexture);
    EXPECT_EQ(p.alphaMode, AlphaMode::Mask);
    EXPECT_EQ(p.alphaCutoff, 0.3);
    EXPECT_TRUE(p.doubleSided);
}

TEST(GltfPbr, SamplersWrapEachAxisTheirOwnWayIncludingMirroredRepeat) {
    PbrMaterial p = pbrOf(R"({"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}})",
                          kImage + R"(, "samplers": [{"wrapS": 33648, "wrapT": 33071}],
                                    "textures": [{"source": 0, "sampler": 0}])");
    EXPECT_EQ(p.baseColorTexture.wrapS, TextureWrap::MirroredRepeat);
    EXPECT_EQ(p.baseColorTexture.wrapT, TextureWrap::Clamp);
}

TEST(GltfPbr, TextureTransformAndTheSecondCoordinateSetAreRead) {
    PbrMaterial p = pbrOf(
        R"({"pbrMetallicRoughness": {"baseColorTexture": {"index": 0, "texCoord": 1,
              "extensions": {"KHR_texture_transform": {"offset": [0.5, 0.25],
                  "rotation": 1.5707963267948966, "scale": [2, 3]}}}}})",
        kImage + R"(, "textures": [{"source": 0}])");
    EXPECT_EQ(p.baseColorTexture.texCoord, 1);
    // T R S: s = cos * 2 u + sin * 3 t + 0.5, t' = -sin * 2 u + cos * 3 t + 0.25.
    const auto& m = p.baseColorTexture.transform;
    EXPECT_NEAR(m[0], 0, 1e-12);
    EXPECT_NEAR(m[1], 3, 1e-12);
    EXPECT_NEAR(m[2], 0.5, 1e-12);
    EXPECT_NEAR(m[3], -2, 1e-12);
    EXPECT_NEAR(m[4], 0, 1e-12);
    EXPECT_NEAR(m[5], 0.25, 1e-12);
    // The transform's own texCoord overrides the slot's.
    PbrMaterial q = pbrOf(
        R"({"pbrMetallicRoughness": {"baseColorTexture": {"index": 0, "texCoord": 1,
              "extensions": {"KHR_texture_transform": {"texCoord": 0}}}}})",
        kImage + R"(, "textures": [{"source": 0}])");
    EXPECT_EQ(q.baseColorTexture.texCoord, 0);
}

TEST(GltfPbr, TransmissionIorAndVolumeAreRead) {
    PbrMaterial p = pbrOf(R"({"extensions": {
            "KHR_materials_transmission": {"transmissionFactor": 0.9,
                                           "transmissionTexture": {"index": 0}},
            "KHR_materials_ior": {"ior": 1.33},
            "KHR_materials_volume": {"thicknessFactor": 0.2, "attenuationDistance": 2,
                                     "attenuationColor": [0.9, 0.5, 0.1]}}})",
                          kImage + R"(, "textures": [{"source": 0}])");
    EXPECT_EQ(p.transmission, 0.9);
    EXPECT_TRUE(p.transmissionTexture);
    EXPECT_EQ(p.ior, 1.33);
    EXPECT_EQ(p.thickness, 0.2);
    EXPECT_EQ(p.attenuationDistance, 2);
    EXPECT_EQ(p.attenuationColor, Vec3(0.9, 0.5, 0.1));
    // Without the volume extension the surface is a thin wall.
    PbrMaterial thin =
        pbrOf(R"({"extensions": {"KHR_materials_transmission": {"transmissionFactor": 1}}})");
    EXPECT_EQ(thin.thickness, 0);
    EXPECT_TRUE(std::isinf(thin.attenuationDistance));
}

TEST(GltfPbr, DefaultsAreTheSpecificationsAndSingleSided) {
    PbrMaterial p = pbrOf("{}");
    EXPECT_EQ(p.baseColor, Vec3(1));
    EXPECT_EQ(p.metallic, 1);
    EXPECT_EQ(p.roughness, 1);
    EXPECT_EQ(p.alphaMode, AlphaMode::Opaque);
    EXPECT_FALSE(p.doubleSided);
    EXPECT_EQ(p.ior, 1.5);
}

TEST(GltfPbr, UnlitKeepsTheBaseColourAndDropsTheEmission) {
    // KHR_materials_unlit: the base colour is all there is; an emission would make a light that
    // no ray but the camera's sees.
    const std::string material = R"({"pbrMetallicRoughness": {"baseColorFactor": [0.2, 0.4, 0.6, 1],
        "baseColorTexture": {"index": 0}}, "emissiveFactor": [1, 1, 1],
        "emissiveTexture": {"index": 0}, "extensions": {"KHR_materials_unlit": {}}})";
    PbrMaterial p = pbrOf(material, kImage + R"(, "textures": [{"source": 0}])");
    EXPECT_TRUE(p.unlit);
    EXPECT_TRUE(p.cutsOut());  // rays other than the camera's pass through
    EXPECT_EQ(p.baseColor, Vec3(0.2, 0.4, 0.6));
    EXPECT_TRUE(p.baseColorTexture);
    EXPECT_EQ(p.emissive, Vec3(0));
    EXPECT_FALSE(p.emissiveTexture);
    EXPECT_FALSE(pbrOf("{}").unlit);
}

TEST(GltfPbr, VolumeScatterFillsTheVolumeWithAMediumOfItsAlbedo) {
    // KHR_materials_volume_scatter: extinction from KHR_materials_volume's attenuation
    // (-ln 0.5 / 0.1 in every channel), scattering by the single-scattering albedo whose
    // multi-scatter albedo the file gives: none for 0, nearly all for 1.
    auto parsed = [](const std::string& scatter, const std::string& volume) {
        std::string text = gltfText(kTriangleScene + std::string(R"(, "materials": [{
            "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1},
              "KHR_materials_volume": )" + volume + R"(,
              "KHR_materials_volume_scatter": )" + scatter + "}}]"),
                                    kTriangle);
        text.replace(text.find(R"({"POSITION": 0})"), 15, R"({"POSITION": 0}, "material": 0)");
        std::vector<Diagnostic> w;
        Model model = parseGltf(text, dataPath("t.gltf"), w, {});
        return std::pair{model.meshes.at(0).materials.at(0), w};
    };
    const std::string volume =
        R"({"thicknessFactor": 1, "attenuationDistance": 0.1, "attenuationColor": [0.5, 0.5, 0.5]})";
    auto [m, warnings] =
        parsed(R"({"multiscatterColor": [0, 0.5, 1], "scatterAnisotropy": 0.3})", volume);
    EXPECT_TRUE(warnings.empty());
    ASSERT_TRUE(m.interior);
    const double sigmaT = -std::log(0.5) / 0.1;
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(m.interior->sigmaT()[k], sigmaT, 1e-9);
    EXPECT_NEAR(m.interior->sigmaS.x, 0, 1e-3 * sigmaT);  // black multi-scatter albedo: absorbs
    EXPECT_GT(m.interior->sigmaS.y, 0.8 * sigmaT);        // 0.5 after many bounces: ~0.9 per bounce
    EXPECT_LT(m.interior->sigmaS.y, 0.95 * sigmaT);
    EXPECT_NEAR(m.interior->sigmaS.z, sigmaT, 1e-3 * sigmaT);  // white: all scatters
    EXPECT_EQ(m.interior->g, 0.3);
    // The medium absorbs now: the surface's own Beer-Lambert pass is off.
    EXPECT_FALSE(std::isfinite(m.pbr->attenuationDistance));
    // Without an attenuation distance there is nothing to scatter: said, and no medium.
    auto [bare, said] = parsed(R"({"multiscatterColor": [1, 1, 1]})", R"({"thicknessFactor": 1})");
    EXPECT_FALSE(bare.interior);
    ASSERT_EQ(said.size(), 1u);
    EXPECT_THAT(said[0].message, HasSubstr("has nothing to scatter"));
}

TEST(GltfPbr, OcclusionTexturesAreSaidToBeUnneeded) {
    std::vector<Diagnostic> warnings;
    pbrOf(R"({"occlusionTexture": {"index": 0}})", kImage + R"(, "textures": [{"source": 0}])",
          &warnings);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_THAT(warnings[0].message, HasSubstr("occlusion"));
}

TEST(GltfPbr, ATextureTransformMustHaveFiniteNumbers) {
    std::string text = gltfText(kTriangleScene + ", " + kImage + R"(, "textures": [{"source": 0}],
        "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0,
            "extensions": {"KHR_texture_transform": {"offset": [1, "a"]}}}}}])",
                                kTriangle);
    text.replace(text.find(R"({"POSITION": 0})"), 15, R"({"POSITION": 0}, "material": 0)");
    Diagnostic d = errorParsing(text);
    EXPECT_THAT(d.message, HasSubstr("KHR_texture_transform offset must be two numbers"));
}

}  // namespace
}  // namespace glint::test
