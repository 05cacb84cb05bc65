// The glTF loader (io/gltf/gltf_loader.h): node trees, meshes and their accessors, materials,
// cameras and lights, and the scenes made of glTF files. Files are in tests/data/gltf (written
// by make_gltf.py there, see PROVENANCE.md); variations are written here as JSON text. Errors
// are in gltf_errors_test.cpp.

#include "glint/io/gltf/gltf_loader.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numbers>
#include <optional>
#include <string>

#include "glint/io/course/course_loader.h"
#include "glint/io/image/texture_io.h"
#include "glint/io/obj/obj_loader.h"
#include "glint/io/registry.h"
#include "unit/io/gltf/gltf_test_support.h"
#include "unit/test_support.h"

namespace glint {
namespace {

using namespace glint::test;
using ::testing::HasSubstr;

/// A scene with `model` placed, triangles without a material grey, prepared.
std::unique_ptr<Scene> place(const Model& model, const Transform& t = Transform()) {
    SceneBuilder builder;
    Material grey;
    grey.diffuse = Vec3(0.5);
    placeModel(builder, model, t, builder.addMaterial(grey));
    auto scene = builder.finish();
    scene->prepare();
    return scene;
}

Vec3 position(const MeshData& mesh, size_t triangle, int corner) {
    return Vec3(mesh.positions[mesh.triangles[triangle].corners[corner].position]);
}

// ---- Nodes and meshes ----

TEST(GltfLoader, NestedNodeTransformsOfTheDefaultSceneArePlaced) {
    Model model = load("nodes.gltf");
    // Scene 1 is the default: its tree places the mesh twice; scene 0's node is not placed.
    ASSERT_EQ(model.placements.size(), 2u);
    ASSERT_EQ(model.meshes.size(), 1u);
    // Node "trs": the parent's translation (1, 2, 3), then 90 degrees about z, then scale 2.
    EXPECT_EQ(model.placements[0].node, 1u);
    expectNear(model.placements[0].worldFromObject.point({1, 0, 0}), {1, 4, 3}, 1e-12);
    expectNear(model.placements[0].worldFromObject.point({0, 1, 0}), {-1, 2, 3}, 1e-12);
    // Node "matrix": a translation by 10 along x (column-major), under the same parent.
    EXPECT_EQ(model.placements[1].node, 2u);
    expectNear(model.placements[1].worldFromObject.point({1, 0, 0}), {12, 2, 3}, 1e-12);
    auto scene = place(model);
    EXPECT_EQ(scene->primitives.triangleCount() + scene->primitives.instancedTriangleCount(), 2u);
    EXPECT_TRUE(shoot(*scene, {0.8, 2.5, 10}, {0, 0, -1}));   // inside the rotated triangle
    EXPECT_TRUE(shoot(*scene, {11.2, 2.2, 10}, {0, 0, -1}));  // inside the translated one
    EXPECT_FALSE(shoot(*scene, {0.2, 0.2, 10}, {0, 0, -1}));  // where the unplaced one was
}

TEST(GltfLoader, AMeshPlacedByTwoNodesIsOneMeshData) {
    Model model = load("scene.glb");
    // Nodes 0 and 1 place the crate (mesh 0): one MeshData, referenced twice.
    ASSERT_GE(model.placements.size(), 2u);
    EXPECT_EQ(model.placements[0].mesh, 0u);
    EXPECT_EQ(model.placements[1].mesh, 0u);
    EXPECT_EQ(model.meshes.size(), 3u);
    EXPECT_EQ(model.meshes[0].triangles.size(), 12u);
    EXPECT_EQ(model.triangles(), 2 * 12 + 2 + model.meshes[2].triangles.size());
    SceneBuilder builder;
    placeModel(builder, model, Transform(), builder.addMaterial(Material{}));
    std::vector<Diagnostic> warnings;
    std::unique_ptr<Scene> scene = builder.finish(&warnings);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_EQ(warnings[0].message,  // the ball's poles
              "48 triangles have zero area once placed and are skipped");
    // The crate is stored once and placed twice; the other meshes are placed once, as triangles.
    EXPECT_EQ(scene->primitives.instanceCount(), 2u);
    EXPECT_EQ(scene->sharedTriangleCount(), 12u);
    EXPECT_EQ(scene->primitives.triangleCount() + scene->primitives.instancedTriangleCount(),
              model.triangles() - 48);
}

TEST(GltfLoader, WithoutScenesEveryRootNodeIsPlaced) {
    Model model = parse(gltfText(kTriangleViews + R"(,
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
        "nodes": [{"mesh": 0, "children": [1]}, {"mesh": 0, "translation": [5, 0, 0]},
                  {"mesh": 0, "translation": [0, 5, 0]}])",
                                 kTriangle));
    ASSERT_EQ(model.placements.size(), 3u);  // node 0, its child 1, and root node 2
    expectNear(model.placements[2].worldFromObject.point(Vec3(0)), {0, 5, 0});
}

TEST(GltfLoader, IndexedTrianglesWithNormalsAndTextureCoordinates) {
    Model model = load("quad.gltf");
    ASSERT_EQ(model.meshes.size(), 1u);
    const MeshData& mesh = model.meshes[0];
    EXPECT_EQ(mesh.positions.size(), 4u);
    ASSERT_EQ(mesh.triangles.size(), 2u);
    EXPECT_EQ(mesh.normalTriangles, 2u);
    EXPECT_EQ(mesh.uvTriangles, 2u);
    expectNear(position(mesh, 1, 0), {0, 0, 0});
    expectNear(position(mesh, 1, 1), {1, 1, 0});
    expectNear(position(mesh, 1, 2), {0, 1, 0});
    // glTF's (0, 1) at the bottom-left corner is Glint's (0, 0): v runs up the image.
    const MeshData::Corner& c = mesh.triangles[0].corners[0];
    EXPECT_EQ(mesh.uvs[c.uv][0], 0.0f);
    EXPECT_EQ(mesh.uvs[c.uv][1], 0.0f);
    const MeshData::Corner& top = mesh.triangles[1].corners[2];  // (0, 1, 0)
    EXPECT_EQ(mesh.uvs[top.uv][1], 1.0f);
    expectNear(Vec3(mesh.normals[c.normal]), {0, 0, 1});
}

TEST(GltfLoader, NonIndexedTrianglesWithoutNormalsAreShadedFlat) {
    std::vector<Diagnostic> warnings;
    Model model = load("modes.gltf", &warnings);
    const MeshData& mesh = model.meshes[0];
    // Strip (2) + fan (2) + non-indexed (1); the points primitive is skipped with a warning.
    ASSERT_EQ(mesh.triangles.size(), 5u);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_THAT(warnings[0].message, HasSubstr("primitive 2: points and lines"));
    const MeshData::Triangle& last = mesh.triangles[4];
    EXPECT_EQ(last.corners[0].normal, MeshData::kNone);
    expectNear(position(mesh, 4, 1), {1, 0, 1});
    auto scene = place(model);
    auto si = shoot(*scene, {0.2, 0.2, 5}, {0, 0, -1});  // the z = 1 triangle, first hit
    ASSERT_TRUE(si);
    expectNear(si->p, {0.2, 0.2, 1}, 1e-6);
    expectNear(si->n, si->ng);
    expectNear(si->ng, {0, 0, 1});
}

TEST(GltfLoader, StripsAndFansKeepTheirWinding) {
    std::vector<Diagnostic> warnings;
    Model model = load("modes.gltf", &warnings);
    const MeshData& mesh = model.meshes[0];
    // Vertices (0,0) (1,0) (0,1) (1,1): every triangle faces +z (counter-clockwise).
    for (size_t t = 0; t < 4; ++t) {
        Vec3 n = cross(position(mesh, t, 1) - position(mesh, t, 0),
                       position(mesh, t, 2) - position(mesh, t, 0));
        EXPECT_GT(n.z, 0) << "triangle " << t;
    }
    // The strip's second triangle is 1 3 2 (turned), the fan's first 1 3 0.
    EXPECT_EQ(mesh.triangles[1].corners[0].position, 1u);
    EXPECT_EQ(mesh.triangles[1].corners[1].position, 3u);
    EXPECT_EQ(mesh.triangles[1].corners[2].position, 2u);
    EXPECT_EQ(mesh.triangles[2].corners[0].position, 1u);
    EXPECT_EQ(mesh.triangles[2].corners[2].position, 0u);
    // The fan's texture coordinates are normalised bytes: 255 is 1, and v is turned up.
    const MeshData::Corner& c = mesh.triangles[2].corners[0];  // vertex 1: bytes (255, 255)
    EXPECT_EQ(mesh.uvs[c.uv][0], 1.0f);
    EXPECT_EQ(mesh.uvs[c.uv][1], 0.0f);
    EXPECT_EQ(mesh.uvTriangles, 2u);
}

TEST(GltfLoader, VertexNormalsAreInterpolated) {
    Model model = load("smooth.gltf");
    EXPECT_EQ(model.meshes[0].normalTriangles, 1u);
    auto scene = place(model);
    auto si = shoot(*scene, {0.02, 0.01, 5}, {0, 0, -1});  // near vertex 0, normal (-1, 0, 1)
    ASSERT_TRUE(si);
    expectNear(si->ng, {0, 0, 1});
    EXPECT_LT(si->n.x, -0.6);
    auto mid = shoot(*scene, {0.5, 0.01, 5}, {0, 0, -1});  // between vertices 0 and 1
    ASSERT_TRUE(mid);
    EXPECT_NEAR(mid->n.x, 0, 0.05);
}

TEST(GltfLoader, SparseAccessorsReplaceElements) {
    Model model = load("sparse.gltf");
    const MeshData& mesh = model.meshes[0];
    ASSERT_EQ(mesh.triangles.size(), 1u);
    expectNear(position(mesh, 0, 0), {0, 0, 0});
    expectNear(position(mesh, 0, 1), {1, 0, 0});
    expectNear(position(mesh, 0, 2), {0, 1, 0});
}

TEST(GltfLoader, TheBinaryFileLoadsAsTheTextOne) {
    Model text = load("quad.gltf"), binary = load("quad.glb");
    const MeshData &a = text.meshes[0], &b = binary.meshes[0];
    ASSERT_EQ(a.positions.size(), b.positions.size());
    ASSERT_EQ(a.triangles.size(), b.triangles.size());
    for (size_t i = 0; i < a.positions.size(); ++i) {
        expectNear(Vec3(a.positions[i]), Vec3(b.positions[i]));
        EXPECT_EQ(a.uvs[i], b.uvs[i]);
    }
    // The texture: an external PNG in one, embedded in a bufferView in the other.
    ASSERT_TRUE(a.materials.at(0).texture && b.materials.at(0).texture);
    const TextureImage& ia = *a.materials[0].texture->image;
    const TextureImage& ib = *b.materials[0].texture->image;
    EXPECT_EQ(ia.rgb, ib.rgb);
    EXPECT_EQ(ib.width, 2);
    EXPECT_EQ(b.materials[0].texture->wrap, TextureWrap::Clamp);
}

TEST(GltfLoader, DataUriBuffersNeedNoFile) {
    GltfOptions options;
    options.limits.readFiles = false;
    Model model = load("nodes.gltf", nullptr, options);
    EXPECT_EQ(model.meshes[0].triangles.size(), 1u);
}

// ---- Materials ----

const MeshMaterial& materialOf(const Model& model, size_t mesh) {
    return model.meshes.at(mesh).materials.at(0);
}

TEST(GltfMaterials, MetallicRoughnessMapping) {
    Model model = load("materials.gltf");
    ASSERT_EQ(model.meshes.size(), 7u);
    // A dielectric: diffuse = base, specular = 0.04, GGX alpha = roughness^2.
    const Material& plastic = materialOf(model, 0).material;
    expectNear(plastic.diffuse, {0.8, 0.2, 0.1});
    expectNear(plastic.specular, Vec3(0.04));
    EXPECT_DOUBLE_EQ(plastic.roughness, 0.25);
    expectNear(plastic.ambient, Vec3(0.8, 0.2, 0.1) * kMtlAmbientLight);
    EXPECT_FALSE(plastic.transmissive());
    EXPECT_EQ(materialOf(model, 0).name, "plastic");
    // A smooth metal: no diffuse, the base colour as the mirror's colour.
    const Material& gold = materialOf(model, 1).material;
    expectNear(gold.diffuse, Vec3(0));
    expectNear(gold.specular, {1, 0.8, 0.3});
    EXPECT_EQ(gold.roughness, 0);
    EXPECT_EQ(gold.shininess, 1000);
    // glTF's default material: white, metallic 1, roughness 1.
    const Material& plain = materialOf(model, 2).material;
    expectNear(plain.specular, Vec3(1));
    EXPECT_EQ(plain.roughness, 1);
    // Emission times KHR_materials_emissive_strength; single-sided, so from the front only.
    expectNear(materialOf(model, 3).material.emission, {4, 2, 1});
    EXPECT_TRUE(materialOf(model, 3).material.frontEmissionOnly);
    // Alpha blending, a quarter opaque: the traversal lets rays through with probability
    // 0.75 (Scene::intersect), so the flat material itself is opaque, or light would pass
    // twice.
    const Material& veil = materialOf(model, 4).material;
    ASSERT_TRUE(materialOf(model, 4).pbr);
    EXPECT_EQ(materialOf(model, 4).pbr->alphaMode, AlphaMode::Blend);
    EXPECT_EQ(materialOf(model, 4).pbr->alpha, 0.25);
    EXPECT_FALSE(veil.transmissive());
    expectNear(veil.diffuse, Vec3(0.2, 0.4, 0.6));
    expectNear(veil.specular, Vec3(0.04));
    // KHR_materials_transmission and KHR_materials_ior: a refracting glass tinted by its base.
    const Material& glass = materialOf(model, 5).material;
    expectNear(glass.transmission, {0.9, 1, 0.9});
    expectNear(glass.diffuse, Vec3(0));
    EXPECT_DOUBLE_EQ(glass.ior, 1.33);
    // MASK below the cutoff: not there at all.
    const Material& cutout = materialOf(model, 6).material;
    expectNear(cutout.transmission, Vec3(1));
    expectNear(cutout.diffuse + cutout.specular, Vec3(0));
}

TEST(GltfMaterials, BaseColourTextureTimesTheFactor) {
    Model model = load("quad.gltf");
    const MeshMaterial& m = materialOf(model, 0);
    ASSERT_TRUE(m.texture);
    EXPECT_EQ(m.texture->kind, Texture::Kind::Image);
    expectNear(m.texture->a, Vec3(1));  // baseColorFactor x (1 - metallic)
    ASSERT_TRUE(m.texture->image);
    EXPECT_TRUE(m.texture->image->srgb);
    // The top-left texel is red (quadrants.png), and Glint's (0, 1) is the image's top left.
    Vec3 c = m.texture->eval(true, 0.01, 0.99, Vec3(0), Vec3(0));
    EXPECT_GT(c.x, 0.9);
    EXPECT_LT(c.y, 0.1);
    // Placed, the material carries its texture into the scene.
    auto scene = place(model);
    ASSERT_EQ(scene->textures.size(), 1u);
    auto si = shoot(*scene, {0.1, 0.9, 5}, {0, 0, -1});
    ASSERT_TRUE(si);
    EXPECT_TRUE(si->hasUv);
    EXPECT_NEAR(si->u, 0.1, 1e-6);
    EXPECT_NEAR(si->v, 0.9, 1e-6);
}

TEST(GltfMaterials, TrianglesWithoutAMaterialTakeThePlacingDefault) {
    Model model = load("nodes.gltf");
    EXPECT_TRUE(model.meshes[0].materials.empty());
    EXPECT_EQ(model.meshes[0].triangles[0].material, MeshData::kNone);
    auto scene = place(model);
    auto si = shoot(*scene, {0.8, 2.5, 10}, {0, 0, -1});
    ASSERT_TRUE(si);
    expectNear(scene->materials[si->material].diffuse, Vec3(0.5));  // place()'s grey
}

TEST(GltfMaterials, AMissingTextureIsAWarningAndTheFactorStays) {
    std::vector<Diagnostic> warnings;
    Model model = load("missing-texture.gltf", &warnings);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_EQ(warnings[0].loc.file, dataPath("missing-texture.gltf"));
    EXPECT_THAT(warnings[0].message, HasSubstr("material 0 'painted': cannot read texture '" +
                                               dataPath("nowhere.png") + "': No such file"));
    EXPECT_THAT(warnings[0].message, HasSubstr("its faces show its base colour factor instead"));
    const MeshMaterial& m = materialOf(model, 0);
    EXPECT_FALSE(m.texture);
    expectNear(m.material.diffuse, {0, 0, 0});  // metallic 1 by default: a green metal
    expectNear(m.material.specular, {0.2, 0.6, 0.2});
}

TEST(GltfMaterials, AWebpImageOfExtTextureWebpTakesThePlaceOfItsFallback) {
    // Required, as a file whose textures are WebP alone would have it.
    std::string text = gltfText(kTriangleScene + R"(,
        "extensionsUsed": ["EXT_texture_webp"], "extensionsRequired": ["EXT_texture_webp"],
        "images": [{"uri": "quadrants.png"}, {"uri": "quadrants_alpha.webp"}],
        "textures": [{"source": 0, "extensions": {"EXT_texture_webp": {"source": 1}}}],
        "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}])",
                                kTriangle);
    text.replace(text.find(R"({"POSITION": 0})"), 15, R"({"POSITION": 0}, "material": 0)");
    std::vector<Diagnostic> warnings;
    if (!decodesWebp()) {
        try {
            parseGltf(text, dataPath("webp.gltf"), warnings);
            ADD_FAILURE() << "a build without WebP accepted a file that requires it";
        } catch (const SceneError& e) {
            EXPECT_THAT(e.what(), HasSubstr("requires extension EXT_texture_webp"));
        }
        return;
    }
    Model model = parseGltf(text, dataPath("webp.gltf"), warnings);
    EXPECT_TRUE(warnings.empty()) << warnings.front().format("warning");
    const MeshMaterial& m = materialOf(model, 0);
    ASSERT_TRUE(m.texture);
    ASSERT_TRUE(m.texture->image);
    EXPECT_EQ(m.texture->image->width, 4);  // the WebP's 4 x 2, not the PNG's
    EXPECT_EQ(m.texture->image->height, 2);
    EXPECT_THAT(m.texture->image->name, HasSubstr("quadrants_alpha.webp"));
}

// KHR_materials_variants: two variants of a triangle's material, chosen by name or number;
// the file's own material without one; an unknown variant is an error that lists them.
TEST(GltfMaterials, AMaterialVariantIsChosenByNameOrNumber) {
    std::string text = gltfText(kTriangleViews + R"(,
        "extensionsUsed": ["KHR_materials_variants"],
        "extensions": {"KHR_materials_variants": {"variants": [{"name": "Red"}, {"name": "Blue"}]}},
        "materials": [
          {"name": "grey", "pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.5, 0.5, 1], "metallicFactor": 0}},
          {"name": "red", "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0, 0, 1], "metallicFactor": 0}},
          {"name": "blue", "pbrMetallicRoughness": {"baseColorFactor": [0, 0, 0.8, 1], "metallicFactor": 0}}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "material": 0,
          "extensions": {"KHR_materials_variants": {"mappings": [
            {"material": 1, "variants": [0]}, {"material": 2, "variants": [1]}]}}}]}],
        "nodes": [{"mesh": 0}])",
                                kTriangle);
    auto diffuseOf = [&](const std::string& variant) {
        GltfOptions options;
        options.variant = variant;
        std::vector<Diagnostic> warnings;
        Model model = parseGltf(text, "t.gltf", warnings, options);
        EXPECT_TRUE(warnings.empty()) << warnings.front().format("warning");
        EXPECT_EQ(model.extensions.size(), 1u);
        if (!model.extensions.empty()) {
            EXPECT_THAT(model.extensions[0].support, HasSubstr("0 'Red', 1 'Blue'"));
        }
        return materialOf(model, 0).material.diffuse;
    };
    expectNear(diffuseOf(""), Vec3(0.5));
    expectNear(diffuseOf("Red"), {0.8, 0, 0});
    expectNear(diffuseOf("1"), {0, 0, 0.8});
    GltfOptions options;
    options.variant = "Green";
    Diagnostic d = errorParsing(text, options);
    EXPECT_THAT(d.message, HasSubstr("--variant Green: no such material variant: its variants are "
                                     "0 'Red', 1 'Blue'"));
    options.variant = "Red";
    d = errorParsing(gltfText(kTriangleScene, kTriangle), options);
    EXPECT_THAT(d.message, HasSubstr("the file has no material variants"));
}

TEST(GltfMaterials, NoImageFileIsReadWhenReadingFilesIsOff) {
    GltfOptions options;
    options.limits.readFiles = false;
    std::vector<Diagnostic> warnings;
    std::string text = gltfText(kTriangleScene + R"(,
        "images": [{"uri": "quadrants.png"}], "textures": [{"source": 0}],
        "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}])",
                                kTriangle);
    text.replace(text.find(R"({"POSITION": 0})"), 15, R"({"POSITION": 0}, "material": 0)");
    Model model = parse(text, &warnings, options);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_THAT(warnings[0].message, HasSubstr("is not read: reading files is off"));
}

// ---- Cameras and lights ----

TEST(GltfLoader, TheCameraAndLightsAreImported) {
    Model model = load("scene.glb");
    ASSERT_TRUE(model.camera);
    const CameraSpec& c = model.camera->spec;
    expectNear(c.eye, {0.3, 1.8, 4.2}, 1e-6);
    Vec3 view = normalize(c.center - c.eye);
    expectNear(view, normalize(Vec3{0, 0.4, 0} - Vec3{0.3, 1.8, 4.2}), 1e-6);
    EXPECT_NEAR(dot(c.up, view), 0, 1e-6);
    EXPECT_GT(c.up.y, 0.9);
    EXPECT_NEAR(c.fovyDegrees, 0.7 * 180 / std::numbers::pi, 1e-9);
    EXPECT_NEAR(model.camera->aspectRatio, 16.0 / 9, 1e-6);
    EXPECT_EQ(model.camera->description, "camera 0 'view' (node 3 'camera')");

    ASSERT_EQ(model.lights.size(), 2u);
    const LightSpec& bulb = model.lights[0];
    EXPECT_EQ(bulb.kind, LightSpec::Kind::Point);
    expectNear(bulb.position, {2, 3, 2.5});
    expectNear(bulb.attenuation, {0, 0, 1});
    expectNear(bulb.color, Vec3(1, 0.9, 0.8) * 30.0, 1e-9);  // candela, as radiant intensity
    const LightSpec& sun = model.lights[1];
    EXPECT_EQ(sun.kind, LightSpec::Kind::Directional);
    expectNear(sun.color, Vec3(1.2), 1e-12);  // lux, as irradiance
    // The node turns -50 degrees about (1, 0.6, 0): its +z, towards the light, is raised.
    EXPECT_NEAR(length(sun.direction), 1, 1e-12);
    EXPECT_GT(sun.direction.y, 0.5);
}

TEST(GltfLoader, SpotLightsShineAlongTheirNodesMinusZWithinTheirConesAndOrthographicIsIgnored) {
    std::vector<Diagnostic> warnings;
    // Light 0 turned 90 degrees about x (its -z to -y: down); light 1 with the spec's default
    // cone; light 2 with cone angles out of the spec's bounds.
    Model model = parse(gltfText(kTriangleViews + R"(,
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
        "cameras": [{"type": "orthographic",
                     "orthographic": {"xmag": 1, "ymag": 1, "znear": 0.1, "zfar": 10}}],
        "extensions": {"KHR_lights_punctual": {"lights": [
            {"type": "spot", "intensity": 2, "range": 3,
             "spot": {"innerConeAngle": 0.2, "outerConeAngle": 0.5}},
            {"type": "spot", "color": [1, 0.5, 0.25], "spot": {}},
            {"type": "spot", "spot": {"innerConeAngle": 0.9, "outerConeAngle": 0.4}}]}},
        "nodes": [{"mesh": 0, "camera": 0},
                  {"translation": [0, 2, 0], "rotation": [-0.70710678, 0, 0, 0.70710678],
                   "extensions": {"KHR_lights_punctual": {"light": 0}}},
                  {"extensions": {"KHR_lights_punctual": {"light": 1}}},
                  {"extensions": {"KHR_lights_punctual": {"light": 2}}}])",
                                 kTriangle),
                        &warnings);
    EXPECT_FALSE(model.camera);
    ASSERT_EQ(model.lights.size(), 3u);
    const LightSpec& down = model.lights[0];
    EXPECT_EQ(down.kind, LightSpec::Kind::Spot);
    expectNear(down.position, {0, 2, 0});
    expectNear(down.axis, {0, -1, 0}, 1e-7);
    expectNear(down.color, Vec3(2), 1e-12);  // candela as they are
    EXPECT_NEAR(down.cosInner, std::cos(0.2), 1e-12);
    EXPECT_NEAR(down.cosOuter, std::cos(0.5), 1e-12);
    EXPECT_EQ(down.range, 3);
    const LightSpec& plain = model.lights[1];
    EXPECT_EQ(plain.kind, LightSpec::Kind::Spot);
    expectNear(plain.axis, {0, 0, -1});
    EXPECT_NEAR(plain.cosInner, 1, 1e-12);
    EXPECT_NEAR(plain.cosOuter, std::cos(std::numbers::pi / 4), 1e-9);
    EXPECT_EQ(plain.range, 0);  // none: unlimited
    const LightSpec& odd = model.lights[2];
    EXPECT_GT(odd.cosInner, odd.cosOuter);
    EXPECT_NEAR(odd.cosOuter, std::cos(0.4), 1e-12);
    ASSERT_EQ(warnings.size(), 2u);
    EXPECT_THAT(warnings[0].message, HasSubstr("camera 0 (node 0) is orthographic"));
    EXPECT_THAT(warnings[1].message, HasSubstr("light 2: its cone angles (inner 0.9, outer 0.4)"));
}

// ---- Integration: glint model.gltf and the mesh command ----

TEST(GltfScene, TheFileCameraAndLightsAreUsedAndItsAspectRatioSizesTheImage) {
    std::vector<Diagnostic> warnings;
    ModelScene m = loadModelScene(dataPath("scene.glb"), warnings, 0, 0, {}, ModelLook::classic());
    EXPECT_TRUE(warnings.empty());
    EXPECT_EQ(m.note, "");  // nothing assumed
    EXPECT_EQ(m.scene->width, 640);
    EXPECT_EQ(m.scene->height, 360);
    ASSERT_TRUE(m.scene->camera);
    expectNear(m.scene->camera->eye, {0.3, 1.8, 4.2}, 1e-6);
    EXPECT_EQ(m.scene->lights.size(), 2u);
    EXPECT_EQ(m.scene->primitives.planeCount(), 0u);  // no floor of Glint's
    // A size given wins over the camera's aspect ratio.
    ModelScene sized = loadModelScene(dataPath("scene.glb"), warnings, 100, 100);  // studio
    EXPECT_EQ(sized.scene->lights.size(), 2u);  // its own, with the studio environment
    EXPECT_EQ(sized.scene->height, 100);
}

TEST(GltfScene, ABareModelIsFramedAsAnObjIs) {
    std::vector<Diagnostic> warnings;
    ModelScene m = loadModelScene(dataPath("quad.glb"), warnings, 0, 0, {}, ModelLook::classic());
    EXPECT_THAT(m.note, HasSubstr("quad.glb has no camera or lights: framing it with a camera at"));
    EXPECT_EQ(m.scene->lights.size(), 2u);
    EXPECT_EQ(m.scene->primitives.planeCount(), 1u);
    EXPECT_EQ(m.scene->height, 480);
}

class GltfSceneFile : public test::TempDirTest {};

TEST_F(GltfSceneFile, OnlyWhatIsMissingIsAdded) {
    const std::string light = R"("extensions": {"KHR_lights_punctual": {"lights": [
            {"type": "directional"}]}},
        "nodes": [{"mesh": 0}, {"extensions": {"KHR_lights_punctual": {"light": 0}}}])";
    std::ofstream(path("lit.gltf")) << gltfText(kTriangleViews + R"(,
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}], )" +
                                                    light,
                                                kTriangle);
    std::vector<Diagnostic> warnings;
    ModelScene m = loadModelScene(path("lit.gltf"), warnings, 0, 0, {}, ModelLook::classic());
    EXPECT_THAT(m.note, HasSubstr("lit.gltf has no camera: framing it with a camera at"));
    EXPECT_THAT(m.note, HasSubstr("(and 1 light of its own)"));
    ASSERT_EQ(m.scene->lights.size(), 1u);  // the file's, not Glint's key and fill
    expectNear(m.scene->lights[0].direction, {0, 0, 1});
    EXPECT_EQ(m.scene->primitives.planeCount(), 1u);
}

TEST(GltfScene, TheMeshCommandPlacesEveryNodeUnderTheTransform) {
    std::vector<Diagnostic> warnings;
    // nodes.gltf has no materials: its triangles take the scene's current material.
    auto scene = parseCourseScene(
        "camera 0 0 5 0 0 0 0 1 0 45\ndiffuse 1 0 0\ntranslate 0 0 -20\nmesh nodes.gltf\n"
        "mesh nodes.gltf\n",
        dataPath("scene.test"), warnings);
    EXPECT_TRUE(warnings.empty());
    // Two nodes, each placing one triangle, placed twice: stored once, four instances.
    EXPECT_EQ(scene->primitives.triangleCount() + scene->primitives.instancedTriangleCount(), 4u);
    EXPECT_EQ(scene->primitives.instanceCount(), 4u);
    scene->prepare();
    auto si = shoot(*scene, {11.2, 2.2, 10}, {0, 0, -1});
    ASSERT_TRUE(si);
    EXPECT_NEAR(si->p.z, 3 - 20, 1e-9);
    expectNear(scene->materials[si->material].diffuse, {1, 0, 0});
}

}  // namespace
}  // namespace glint
