// The extensions a glTF file uses (io/gltf/gltf_extensions.h): every one is reported with what
// Glint does with it, from extensionsUsed and from the objects that carry one, and each that
// Glint ignores is warned of once; the table itself is well formed.

#include "glint/io/gltf/gltf_extensions.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <set>

#include "glint/io/image/texture_io.h"
#include "unit/io/gltf/gltf_test_support.h"

namespace glint::test {
namespace {

using testing::HasSubstr;

/// The triangle with material `material` (JSON), and `extra` top-level members.
std::string withMaterial(const std::string& material, const std::string& extra = "") {
    std::string text = gltfText(kTriangleScene + (extra.empty() ? "" : ", " + extra) +
                                    R"(, "materials": [)" + material + "]",
                                kTriangle);
    text.replace(text.find(R"({"POSITION": 0})"), 15, R"({"POSITION": 0}, "material": 0)");
    return text;
}

/// The support text the model reports for extension `name`; empty if it does not list it.
std::string reported(const Model& model, const std::string& name) {
    for (const FormatExtension& e : model.extensions)
        if (e.name == name) return e.support;
    return "";
}

/// How many warnings name extension `name`.
size_t warningsNaming(const std::vector<Diagnostic>& warnings, const std::string& name) {
    size_t n = 0;
    for (const Diagnostic& d : warnings) n += d.message.find(name) != std::string::npos;
    return n;
}

TEST(GltfExtensions, TheTableNamesEachExtensionOnceWithANoteForWhatIsLeftOut) {
    std::set<std::string_view> names;
    for (const GltfExtension& e : kGltfExtensions) {
        EXPECT_TRUE(names.insert(e.name).second) << e.name << " is listed twice";
        EXPECT_TRUE(e.name.starts_with("KHR_") || e.name.starts_with("EXT_")) << e.name;
        const bool leavesOut =
            e.support == GltfSupport::Partly || e.support == GltfSupport::Ignored;
        EXPECT_EQ(!e.note.empty(), leavesOut) << e.name;
    }
    EXPECT_EQ(gltfSupportText("KHR_texture_transform"), "rendered");
    EXPECT_EQ(gltfSupportText("KHR_materials_clearcoat"), "rendered");
    EXPECT_EQ(gltfSupportText("KHR_lights_punctual"), "rendered");  // spot lights and range too
    EXPECT_THAT(gltfSupportText("KHR_materials_dispersion"), testing::StartsWith("partly: "));
    EXPECT_EQ(
        gltfSupportText("EXT_texture_webp"),
        decodesWebp()
            ? "rendered"
            : std::string(findGltfExtension("EXT_texture_webp")->note).insert(0, "ignored: "));
    EXPECT_EQ(gltfSupportText("KHR_materials_unlit"), "rendered");  // seen by the camera only
    EXPECT_EQ(gltfSupportText("EXT_made_up"), "ignored: Glint does not know this extension");
    EXPECT_TRUE(rendersGltfExtension("KHR_materials_transmission"));
    EXPECT_TRUE(rendersGltfExtension("KHR_lights_punctual"));
    EXPECT_EQ(rendersGltfExtension("EXT_texture_webp"), decodesWebp());
    EXPECT_TRUE(rendersGltfExtension("KHR_materials_variants"));  // --variant
    EXPECT_FALSE(rendersGltfExtension("KHR_texture_basisu"));
    EXPECT_FALSE(rendersGltfExtension("EXT_made_up"));
}

TEST(GltfExtensions, EveryExtensionUsedIsReportedAndEachIgnoredOneWarnedOfOnce) {
    // Clearcoat on two materials, a texture transform inside the clearcoat's texture and
    // specular-glossiness on a material (both found though extensionsUsed forgets them), and one
    // Glint does not know.
    const std::string clearcoat =
        R"("KHR_materials_clearcoat": {"clearcoatFactor": 1,
             "clearcoatTexture": {"index": 0,
               "extensions": {"KHR_texture_transform": {"scale": [2, 2]}}}})";
    const std::string first =
        R"({"extensions": {)" + clearcoat + R"(, "KHR_materials_pbrSpecularGlossiness": {}}})";
    const std::string second = R"({"extensions": {)" + clearcoat + R"(, "EXT_made_up": {}}})";
    std::string text = withMaterial(first + ", " + second,
                                    R"("extensionsUsed": ["KHR_materials_clearcoat",
                                        "KHR_materials_emissive_strength", "EXT_made_up"],
                                    "images": [{"uri": "quadrants.png"}],
                                    "textures": [{"source": 0}])");
    std::vector<Diagnostic> warnings;
    Model model = parse(text, &warnings);
    std::vector<std::string> names;
    for (const FormatExtension& e : model.extensions) names.push_back(e.name);
    EXPECT_THAT(names, testing::ElementsAre("EXT_made_up", "KHR_materials_clearcoat",
                                            "KHR_materials_emissive_strength",
                                            "KHR_materials_pbrSpecularGlossiness",
                                            "KHR_texture_transform"));
    EXPECT_EQ(reported(model, "KHR_texture_transform"), "rendered");
    EXPECT_EQ(reported(model, "KHR_materials_clearcoat"), "rendered");
    EXPECT_EQ(reported(model, "KHR_materials_pbrSpecularGlossiness"),
              gltfSupportText("KHR_materials_pbrSpecularGlossiness"));
    EXPECT_THAT(reported(model, "KHR_materials_pbrSpecularGlossiness"),
                testing::StartsWith("ignored: "));
    // One warning for each ignored extension however often the file uses it, none for those
    // rendered.
    EXPECT_EQ(warningsNaming(warnings, "KHR_materials_clearcoat"), 0u);
    EXPECT_EQ(warningsNaming(warnings, "KHR_materials_pbrSpecularGlossiness"), 1u);
    EXPECT_EQ(warningsNaming(warnings, "EXT_made_up"), 1u);
    EXPECT_EQ(warningsNaming(warnings, "KHR_texture_transform"), 0u);
    EXPECT_EQ(warningsNaming(warnings, "KHR_materials_emissive_strength"), 0u);
    for (const Diagnostic& d : warnings) {
        if (d.message.find("KHR_materials_pbrSpecularGlossiness") != std::string::npos) {
            EXPECT_THAT(d.message,
                        HasSubstr("which Glint does not render: specular-glossiness materials"));
        }
    }
}

TEST(GltfExtensions, ExtensionsOnNodesAndTexturesCountToo) {
    std::string text = gltfText(kTriangleViews + R"(,
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
        "nodes": [{"mesh": 0, "extensions": {"EXT_mesh_gpu_instancing": {"attributes": {}}}}],
        "textures": [{"extensions": {"KHR_texture_basisu": {"source": 0}}}])",
                                kTriangle);
    std::vector<Diagnostic> warnings;
    Model model = parse(text, &warnings);
    EXPECT_THAT(reported(model, "EXT_mesh_gpu_instancing"), testing::StartsWith("ignored: "));
    EXPECT_THAT(reported(model, "KHR_texture_basisu"), testing::StartsWith("ignored: "));
    EXPECT_EQ(warningsNaming(warnings, "EXT_mesh_gpu_instancing"), 1u);
    EXPECT_EQ(warningsNaming(warnings, "KHR_texture_basisu"), 1u);
}

TEST(GltfExtensions, AFileOfRenderedExtensionsAloneLoadsWithoutAWord) {
    std::string text = withMaterial(
        R"({"extensions": {"KHR_materials_transmission": {"transmissionFactor": 1},
                           "KHR_materials_ior": {"ior": 1.4}}})",
        R"("extensionsUsed": ["KHR_materials_transmission", "KHR_materials_ior"],
           "extensionsRequired": ["KHR_materials_transmission"])");
    std::vector<Diagnostic> warnings;
    Model model = parse(text, &warnings);
    EXPECT_TRUE(warnings.empty()) << warnings.front().format("warning");
    ASSERT_EQ(model.extensions.size(), 2u);
    EXPECT_EQ(reported(model, "KHR_materials_ior"), "rendered");
    EXPECT_EQ(reported(model, "KHR_materials_transmission"), "rendered");
    // A file without extensions reports none.
    EXPECT_TRUE(parse(withMaterial("{}")).extensions.empty());
}

TEST(GltfExtensions, AnIgnoredExtensionTheFileRequiresIsAnError) {
    EXPECT_THAT(errorParsing(withMaterial("{}",
                                          R"("extensionsUsed": ["KHR_texture_basisu"],
                                     "extensionsRequired": ["KHR_texture_basisu"])"))
                    .message,
                HasSubstr("the file requires extension KHR_texture_basisu, which Glint does not "
                          "support"));
}

}  // namespace
}  // namespace glint::test
