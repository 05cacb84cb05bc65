// The OBJ loader (io/obj/obj_loader.h) and placing its meshes (scene/mesh.h): the statements it
// reads, MTL materials and textures, and every error with its file, line and column. Files are
// in tests/data/meshes (see PROVENANCE.md there).

#include "glint/io/obj/obj_loader.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <optional>
#include <string>

#include "glint/render/renderer.h"
#include "unit/test_support.h"

namespace glint {
namespace {

using test::expectNear;
using test::shoot;
using ::testing::HasSubstr;

std::string meshPath(const std::string& name) {
    return std::string(GLINT_TEST_DATA_DIR) + "/meshes/" + name;
}

MeshData load(const std::string& name, std::vector<Diagnostic>* warningsOut = nullptr) {
    std::vector<Diagnostic> warnings;
    MeshData mesh = loadObj(meshPath(name), warnings);
    if (warningsOut)
        *warningsOut = warnings;
    else
        EXPECT_TRUE(warnings.empty()) << warnings.front().format("warning");
    return mesh;
}

MeshData parse(const std::string& text, std::vector<Diagnostic>* warningsOut = nullptr,
               const std::string* mtl = nullptr, const std::string& dir = "") {
    std::vector<Diagnostic> warnings;
    ObjOptions options;
    options.mtlText = mtl;
    MeshData mesh = parseObj(text, dir.empty() ? "m.obj" : dir + "/m.obj", warnings, options);
    if (warningsOut)
        *warningsOut = warnings;
    else
        EXPECT_TRUE(warnings.empty()) << warnings.front().format("warning");
    return mesh;
}

/// The error that loading `name` (a file in tests/data/meshes) or parsing `text` reports.
Diagnostic errorLoading(const std::string& name) {
    std::vector<Diagnostic> warnings;
    try {
        loadObj(meshPath(name), warnings);
    } catch (const SceneError& e) {
        return e.diagnostic();
    }
    ADD_FAILURE() << "no SceneError for " << name;
    return {};
}

Diagnostic errorParsing(const std::string& text, const std::string* mtl = nullptr,
                        const LoadLimits& limits = {}) {
    std::vector<Diagnostic> warnings;
    ObjOptions options;
    options.mtlText = mtl;
    options.limits = limits;
    try {
        parseObj(text, "m.obj", warnings, options);
    } catch (const SceneError& e) {
        return e.diagnostic();
    }
    ADD_FAILURE() << "no SceneError for:\n" << text;
    return {};
}

void expectError(const Diagnostic& d, int line, int column, const std::string& message) {
    EXPECT_EQ(d.loc.line, line) << d.format("error");
    EXPECT_EQ(d.loc.column, column) << d.format("error");
    EXPECT_THAT(d.message, HasSubstr(message));
}

/// A scene holding `mesh` placed by `m` (identity by default) with a grey default material.
std::unique_ptr<Scene> place(const MeshData& mesh, const Mat4& m = Mat4::identity()) {
    auto scene = std::make_unique<Scene>();
    Material grey;
    grey.diffuse = Vec3(0.5);
    uint32_t id = scene->addMaterial(grey);
    addMesh(*scene, mesh, *Transform::fromMatrix(m), id);
    scene->prepare();
    return scene;
}

std::optional<SurfaceInteraction> shootDown(const Scene& scene, double x, double y) {
    return shoot(scene, {x, y, 5}, {0, 0, -1});
}

// ---- Statements ----

TEST(ObjLoader, QuadIsSplitIntoTwoTriangles) {
    MeshData mesh = load("quad.obj");
    EXPECT_EQ(mesh.positions.size(), 4u);
    ASSERT_EQ(mesh.triangles.size(), 2u);
    EXPECT_EQ(mesh.normalTriangles, 0u);
    EXPECT_EQ(mesh.uvTriangles, 0u);
    auto scene = place(mesh);
    EXPECT_EQ(scene->primitives.triangleCount(), 2u);
    // Both halves are there, facing +z, and nothing outside the square.
    for (auto [x, y] : {std::pair{0.1, 0.9}, {0.9, 0.1}, {0.5, 0.5}, {0.05, 0.05}}) {
        auto si = shootDown(*scene, x, y);
        ASSERT_TRUE(si) << x << ", " << y;
        expectNear(si->ng, {0, 0, 1});
    }
    EXPECT_FALSE(shootDown(*scene, 1.1, 0.5));
}

TEST(ObjLoader, ConcaveQuadIsSplitAlongItsInsideDiagonal) {
    // A dart whose vertex 2, (2, 1), is reflex: only the diagonal 2-4 lies inside, and it is
    // the longer one (5 against 4).
    MeshData mesh = parse("v 0 0 0\nv 2 1 0\nv 4 0 0\nv 2 6 0\nf 1 2 3 4\n");
    auto scene = place(mesh);
    EXPECT_TRUE(shootDown(*scene, 2, 3));
    EXPECT_TRUE(shootDown(*scene, 1, 2));
    EXPECT_FALSE(shootDown(*scene, 2, 0.5));  // the notch
}

TEST(ObjLoader, LargerPolygonsAreEarClipped) {
    // An L-shaped hexagon (concave).
    MeshData mesh = parse("v 0 0 0\nv 2 0 0\nv 2 1 0\nv 1 1 0\nv 1 2 0\nv 0 2 0\nf 1 2 3 4 5 6\n");
    EXPECT_EQ(mesh.triangles.size(), 4u);
    auto scene = place(mesh);
    EXPECT_TRUE(shootDown(*scene, 1.5, 0.5));
    EXPECT_TRUE(shootDown(*scene, 0.5, 1.5));
    EXPECT_FALSE(shootDown(*scene, 1.5, 1.5));
}

TEST(ObjLoader, NonPlanarPolygonsBecomeFansWithAWarning) {
    std::vector<Diagnostic> warnings;
    MeshData mesh =
        parse("v 0 0 0\nv 1 0 0\nv 1.5 1 0.5\nv 0.5 1.5 0\nv -0.5 1 0\nf 1 2 3 4 5\n", &warnings);
    EXPECT_EQ(mesh.triangles.size(), 3u);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_EQ(warnings[0].loc.line, 6);
    EXPECT_THAT(warnings[0].message, HasSubstr("split as a fan"));
}

TEST(ObjLoader, NegativeIndicesCountBackFromTheLastDefined) {
    MeshData mesh = load("negative.obj");
    ASSERT_EQ(mesh.triangles.size(), 2u);
    const auto& a = mesh.triangles[0].corners;
    const auto& b = mesh.triangles[1].corners;
    EXPECT_EQ(a[0].position, 0u);
    EXPECT_EQ(a[2].position, 2u);
    EXPECT_EQ(a[1].uv, 1u);
    EXPECT_EQ(a[0].normal, 0u);
    EXPECT_EQ(b[0].position, 3u);
    EXPECT_EQ(b[2].position, 5u);
    EXPECT_EQ(b[0].uv, MeshData::kNone);
    EXPECT_EQ(b[1].normal, 0u);
    EXPECT_EQ(mesh.normalTriangles, 2u);
    EXPECT_EQ(mesh.uvTriangles, 1u);
}

TEST(ObjLoader, MeshesWithoutNormalsAreShadedFlat) {
    MeshData mesh = load("flat.obj");
    EXPECT_EQ(mesh.triangles.size(), 4u);
    auto scene = place(mesh);
    // The slanted face x + y + z = 1, seen from outside.
    auto si = shoot(*scene, {1, 1, 1}, {-1, -1, -1});
    ASSERT_TRUE(si);
    expectNear(si->ng, normalize(Vec3{1, 1, 1}));
    expectNear(si->n, si->ng);
    // The bottom face, z = 0, seen from below.
    auto bottom = shoot(*scene, {0.2, 0.2, -3}, {0, 0, 1});
    ASSERT_TRUE(bottom);
    expectNear(bottom->n, {0, 0, -1});
}

TEST(ObjLoader, VertexNormalsAreInterpolated) {
    MeshData mesh = load("smooth.obj");
    EXPECT_EQ(mesh.normalTriangles, 1u);
    auto scene = place(mesh);
    Vec3 na = normalize(Vec3{-1, 0, 1}), nb = normalize(Vec3{1, 0, 1}),
         nc = normalize(Vec3{0, 1, 1});
    // At (x, y) the barycentrics of B (2, 0) and C (0, 2) are x / 2 and y / 2.
    for (auto [x, y] : {std::pair{2.0 / 3, 2.0 / 3}, {1.0, 0.0}, {0.2, 0.1}, {0.5, 1.2}}) {
        auto si = shootDown(*scene, x, y);
        ASSERT_TRUE(si);
        double b1 = x / 2, b2 = y / 2;
        Vec3 expected = normalize(na * (1 - b1 - b2) + nb * b1 + nc * b2);
        expectNear(si->n, expected, 1e-6);
        expectNear(si->ng, {0, 0, 1});
    }
}

TEST(ObjLoader, NormalsArePlacedByTheInverseTranspose) {
    MeshData mesh = load("smooth.obj");
    // Stretch x by 4, then lift by 1: normals must shrink in x (inverse transpose).
    auto scene = place(mesh, Mat4::translate(0, 0, 1) * Mat4::scale(4, 1, 1));
    auto si = shootDown(*scene, 0.02, 0.01);  // near vertex A, now at (0, 0, 1)
    ASSERT_TRUE(si);
    EXPECT_NEAR(si->p.z, 1, 1e-12);
    Vec3 n = si->n;
    EXPECT_LT(n.x, 0);
    EXPECT_NEAR(n.x / n.z, -0.25, 0.01);      // (-1, 0, 1) by (1/4, 1, 1)
    EXPECT_TRUE(shootDown(*scene, 7, 0.05));  // B moved to x = 8
    EXPECT_FALSE(shootDown(*scene, 9, 0.05));
}

TEST(ObjLoader, PlacementBeyondTheCoordinateRangeIsAnError) {
    MeshData mesh = load("quad.obj");
    Scene scene;
    try {
        addMesh(scene, mesh, *Transform::fromMatrix(Mat4::scale(1e19, 1, 1)), 0);
        FAIL() << "no error";
    } catch (const SceneError& e) {
        EXPECT_THAT(e.diagnostic().message, HasSubstr("vertex 2 lies beyond"));
        EXPECT_THAT(e.diagnostic().loc.file, HasSubstr("quad.obj"));
    }
}

TEST(ObjLoader, DegenerateTrianglesAreCountedAndSkipped) {
    MeshData mesh = parse("v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 4\n");
    Scene scene;
    MeshPlacement placed = addMesh(scene, mesh, Transform(), 0);
    EXPECT_EQ(placed.added, 1u);
    EXPECT_EQ(placed.degenerate, 1u);
}

TEST(ObjLoader, LineEndingsCommentsAndAByteOrderMark) {
    MeshData crlf = parse("\xEF\xBB\xBFv 0 0 0\r\nv 1 0 0\r\n# c\r\nv 0 1 0\r\nf 1 2 3\r\n");
    EXPECT_EQ(crlf.triangles.size(), 1u);
    // Line numbers count CR LF once.
    expectError(errorParsing("v 0 0 0\r\n\r\nf 1 2 3\r\n"), 3, 5, "vertex index '2'");
}

// ---- Materials and textures ----

TEST(ObjLoader, UsemtlGroupsTakeTheirMtlMaterials) {
    MeshData mesh = load("groups.obj");
    ASSERT_EQ(mesh.triangles.size(), 3u);
    ASSERT_EQ(mesh.materials.size(), 2u);
    EXPECT_EQ(mesh.triangles[0].material, MeshData::kNone);
    const MeshMaterial& red = mesh.materials[mesh.triangles[1].material];
    const MeshMaterial& green = mesh.materials[mesh.triangles[2].material];
    EXPECT_EQ(red.name, "red");
    EXPECT_EQ(green.name, "green");
    expectNear(red.material.diffuse, {0.8, 0.1, 0.1}, 1e-6);
    expectNear(green.material.diffuse, {0.1, 0.8, 0.1}, 1e-6);
    // No Ka: 0.2 x Kd. Ka: 0.2 x Ka.
    expectNear(red.material.ambient, {0.16, 0.02, 0.02}, 1e-6);
    expectNear(green.material.ambient, {0.1, 0.1, 0.1}, 1e-6);
    expectNear(red.material.specular, {0, 0, 0});
    expectNear(green.material.specular, {0.25, 0.25, 0.25}, 1e-6);
    EXPECT_EQ(green.material.shininess, 40);

    auto scene = place(mesh);
    auto materialAt = [&](double x) {
        return scene->materials[shootDown(*scene, x, 0.2)->material];
    };
    expectNear(materialAt(0.2).diffuse, {0.5, 0.5, 0.5});
    expectNear(materialAt(2.2).diffuse, {0.8, 0.1, 0.1}, 1e-6);
    expectNear(materialAt(4.2).diffuse, {0.1, 0.8, 0.1}, 1e-6);
}

TEST(ObjLoader, UnknownMaterialsTakeTheDefaultWithOneWarningEach) {
    std::vector<Diagnostic> warnings;
    MeshData mesh = parse(
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl wood\nf 1 2 3\nusemtl wood\nf 1 2 3\nusemtl x\n"
        "f 1 2 3\n",
        &warnings);
    ASSERT_EQ(warnings.size(), 2u);
    EXPECT_EQ(warnings[0].loc.line, 4);
    EXPECT_EQ(warnings[0].loc.column, 8);
    EXPECT_THAT(warnings[0].message, HasSubstr("'wood' is not defined"));
    for (const auto& t : mesh.triangles) EXPECT_EQ(t.material, MeshData::kNone);
}

TEST(ObjLoader, MtlMappingOfIllumDissolveAndIor) {
    const std::string mtl =
        "newmtl matte\nKd 0.5 0.5 0.5\nKs 0.9 0.9 0.9\nillum 1\n"
        "newmtl glass\nKd 0.2 0.2 0.2\nKs 0.1 0.1 0.1\nd 0.25\nNi 1.45\nKe 0.5 0 0\n"
        "newmtl veil\nKd 1 1 1\nTr 0.5\n"
        "newmtl odd\nKd 1 1 1\nd 0.5\nNi 0\nNs -3\n";
    std::vector<Diagnostic> warnings;
    MeshData mesh = parse("mtllib any.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", &warnings, &mtl);
    ASSERT_EQ(mesh.materials.size(), 4u);
    const Material& matte = mesh.materials[0].material;
    expectNear(matte.specular, {0, 0, 0});  // illum 1: no highlights
    const Material& glass = mesh.materials[1].material;
    expectNear(glass.transmission, Vec3(0.75));
    expectNear(glass.diffuse, Vec3(0.05), 1e-7);
    expectNear(glass.specular, Vec3(0.1), 1e-7);
    EXPECT_NEAR(glass.ior, 1.45, 1e-6);
    expectNear(glass.emission, {0.5, 0, 0});
    const Material& veil = mesh.materials[2].material;
    expectNear(veil.transmission, Vec3(0.5));  // Tr is 1 - d
    EXPECT_EQ(veil.ior, 1);                    // no Ni: straight through
    const Material& odd = mesh.materials[3].material;
    EXPECT_EQ(odd.ior, 1);
    EXPECT_EQ(odd.shininess, 0);
    ASSERT_EQ(warnings.size(), 2u);
    EXPECT_EQ(warnings[0].loc.file, "any.mtl");
    EXPECT_EQ(warnings[0].loc.line, 14);
    EXPECT_THAT(warnings[0].message, HasSubstr("negative Ns"));
    EXPECT_THAT(warnings[1].message, HasSubstr("Ni"));
}

TEST(ObjLoader, MtlPbrExtensionsMakeAPhysicallyBasedMaterial) {
    const std::string mtl =
        "newmtl brushed\nKd 0.8 0.6 0.2\nPm 0.9\nPr 0.4\nKe 0 0 0\nNi 1.7\nd 0.5\n"
        "newmtl classic\nKd 0.5 0.5 0.5\nKs 0.2 0.2 0.2\n"
        "newmtl sheeny\nKd 1 1 1\nPs 0.5\nPc 0.8\nPcr 0.3\naniso 0.6\nanisor 0.25\n";
    std::vector<Diagnostic> warnings;
    MeshData mesh = parse("mtllib any.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", &warnings, &mtl);
    ASSERT_EQ(mesh.materials.size(), 3u);
    ASSERT_TRUE(mesh.materials[0].pbr);
    const PbrMaterial& p = *mesh.materials[0].pbr;
    expectNear(p.baseColor, {0.8, 0.6, 0.2}, 1e-6);
    EXPECT_NEAR(p.metallic, 0.9, 1e-6);
    EXPECT_NEAR(p.roughness, 0.4, 1e-6);
    EXPECT_NEAR(p.ior, 1.7, 1e-6);
    EXPECT_EQ(p.alphaMode, AlphaMode::Blend);
    EXPECT_NEAR(p.alpha, 0.5, 1e-6);
    EXPECT_TRUE(p.doubleSided);
    EXPECT_FALSE(mesh.materials[1].pbr);  // no PBR statement: the classic mapping alone
    ASSERT_TRUE(mesh.materials[2].pbr);
    const PbrMaterial& layers = *mesh.materials[2].pbr;
    expectNear(layers.sheenColor, Vec3(0.5), 1e-6);  // Ps: a white sheen of that strength
    EXPECT_NEAR(layers.clearcoat, 0.8, 1e-6);
    EXPECT_NEAR(layers.clearcoatRoughness, 0.3, 1e-6);
    EXPECT_NEAR(layers.anisotropy, 0.6, 1e-6);
    EXPECT_NEAR(layers.anisotropyRotation, std::numbers::pi / 2, 1e-6);  // anisor in turns
    EXPECT_TRUE(warnings.empty());                                       // every layer is rendered
}

class ObjPbrMaps : public test::TempDirTest {};

TEST_F(ObjPbrMaps, MapsAndNormalMapsAreRead) {
    // map_Bump stands for a normal map, as Blender's exporter writes it.
    std::filesystem::copy_file(meshPath("quadrants.png"), path("q.png"));
    std::ofstream(path("m.mtl")) << "newmtl a\nKd 1 1 1\nPr 1\nmap_Pr q.png\nmap_Pm q.png\n"
                                    "map_Bump -bm 0.5 q.png\nmap_Ke -s 2 2 1 q.png\n";
    std::ofstream(path("m.obj"))
        << "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nusemtl a\n"
           "f 1/1 2/2 3/3\n";
    std::vector<Diagnostic> warnings;
    MeshData mesh = loadObj(path("m.obj"), warnings);
    ASSERT_EQ(mesh.materials.size(), 1u);
    ASSERT_TRUE(mesh.materials[0].pbr);
    const PbrMaterial& p = *mesh.materials[0].pbr;
    EXPECT_TRUE(p.roughnessTexture);
    EXPECT_TRUE(p.metallicTexture);
    ASSERT_TRUE(p.normalTexture);
    EXPECT_FALSE(p.normalTexture.image->srgb);
    EXPECT_NEAR(p.normalScale, 0.5, 1e-6);
    ASSERT_TRUE(p.emissiveTexture);
    EXPECT_EQ(p.emissive, Vec3(1));                        // map_Ke without Ke: the texture alone
    EXPECT_NEAR(p.emissiveTexture.transform[0], 2, 1e-6);  // -s 2 2
    EXPECT_TRUE(warnings.empty());
    // The normal-mapped face gets tangents along +u (+x here), right-handed.
    ASSERT_EQ(mesh.tangents.size(), 3u);
    EXPECT_NEAR(mesh.tangents[0][0], 1, 1e-6);
    EXPECT_EQ(mesh.tangents[0][3], 1);
    EXPECT_NE(mesh.triangles[0].corners[0].tangent, MeshData::kNone);
}

TEST(ObjLoader, TexturedMaterialsCarryTheirImage) {
    MeshData mesh = load("textured.obj");
    EXPECT_EQ(mesh.uvTriangles, 2u);
    EXPECT_EQ(mesh.normalTriangles, 2u);
    ASSERT_EQ(mesh.materials.size(), 1u);
    const MeshMaterial& m = mesh.materials[0];
    ASSERT_TRUE(m.texture);
    EXPECT_EQ(m.texture->kind, Texture::Kind::Image);
    EXPECT_EQ(m.texture->wrap, TextureWrap::Clamp);  // -clamp on
    EXPECT_EQ(m.texture->image->width, 2);
    // No Ka: ambient is 0.2 x Kd x the texture's mean, (1 + 0 + 0 + 1) / 4 per channel.
    expectNear(m.material.ambient, Vec3(0.1));
}

/// Renders `scene` (camera on the +z axis looking at the origin, one directional light along
/// the view) at `w` x `h` and returns the 8-bit image.
Image8 renderFromFront(Scene& scene, int w, int h, double distance = 4) {
    scene.camera = CameraSpec{{0, 0, distance}, {0, 0, 0}, {0, 1, 0}, 45};
    scene.width = w;
    scene.height = h;
    LightSpec l;
    l.kind = LightSpec::Kind::Directional;
    l.direction = {0, 0, 1};
    l.color = {1, 1, 1};
    scene.lights.push_back(l);
    if (!scene.prepared()) scene.prepare();
    RenderOptions o;
    o.threads = 1;
    return toImage8(render(scene, o).film);
}

TEST(ObjLoader, TextureTexelsAppearInTheRender) {
    MeshData mesh = load("textured.obj");
    auto scene = place(mesh);
    Image8 img = renderFromFront(*scene, 32, 32, 3);
    // The square spans about the middle 26 pixels; texel centres are a quarter of the way in.
    // Colour = ambient 0.1 + texel (N.L = 1, no specular): red texel (255, 25, 25).
    auto expectPixel = [&](int x, int y, int r, int g, int b) {
        EXPECT_EQ(img.at(x, y, 0), r) << x << "," << y;
        EXPECT_EQ(img.at(x, y, 1), g) << x << "," << y;
        EXPECT_EQ(img.at(x, y, 2), b) << x << "," << y;
    };
    expectPixel(9, 9, 255, 25, 25);      // top left: red
    expectPixel(22, 9, 25, 255, 25);     // top right: green
    expectPixel(9, 22, 25, 25, 255);     // bottom left: blue
    expectPixel(22, 22, 255, 255, 255);  // bottom right: white
    expectPixel(0, 0, 0, 0, 0);          // background
}

TEST(ObjLoader, AMissingTextureIsAWarningAndTheMaterialKeepsItsColour) {
    std::vector<Diagnostic> warnings;
    MeshData mesh = load("missing-texture.obj", &warnings);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_THAT(warnings[0].loc.file, HasSubstr("missing-texture.mtl"));
    EXPECT_EQ(warnings[0].loc.line, 1);
    EXPECT_THAT(warnings[0].message, HasSubstr("cannot read texture"));
    EXPECT_THAT(warnings[0].message, HasSubstr("textures/nowhere.png"));
    ASSERT_EQ(mesh.materials.size(), 1u);
    EXPECT_FALSE(mesh.materials[0].texture);
    expectNear(mesh.materials[0].material.diffuse, {0.5, 0.25, 0});
}

// ---- Errors ----

TEST(ObjErrors, TruncatedFaceNamesTheFileAndLine) {
    Diagnostic d = errorLoading("truncated.obj");
    EXPECT_THAT(d.loc.file, HasSubstr("truncated.obj"));
    expectError(d, 6, 3, "a face needs at least 3 vertices, got 2");
}

TEST(ObjErrors, OutOfRangeIndex) {
    Diagnostic d = errorLoading("out-of-range.obj");
    expectError(d, 5, 7, "vertex index '9' is out of range: 3 vertices are defined before it");
}

TEST(ObjErrors, FileWithoutFaces) {
    Diagnostic d = errorLoading("no-faces.obj");
    EXPECT_THAT(d.loc.file, HasSubstr("no-faces.obj"));
    EXPECT_THAT(d.message, HasSubstr("the mesh has no faces"));
}

TEST(ObjErrors, MissingFileAndDirectory) {
    Diagnostic d = errorLoading("nowhere.obj");
    EXPECT_THAT(d.message, HasSubstr("cannot read mesh: No such file or directory"));
    std::vector<Diagnostic> warnings;
    EXPECT_THROW(loadObj(meshPath(""), warnings), SceneError);
}

TEST(ObjErrors, IndicesAndNumbers) {
    const std::string tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    expectError(errorParsing(tri + "f 0 1 2\n"), 4, 3, "vertex index '0' is not valid");
    expectError(errorParsing(tri + "f 1 2 -4\n"), 4, 7,
                "vertex index '-4' counts back past the first vertex: 3 vertices are defined");
    expectError(errorParsing("f 1 2 3\n"), 1, 3, "none is defined before it");
    expectError(errorParsing(tri + "vn 0 0 1\nf 1//1 2//2 3//1\n"), 5, 8,
                "normal index '2' is out of range: 1 normal is defined before it");
    expectError(errorParsing(tri + "f 1/1 2/1 3/1\n"), 4, 3,
                "texture coordinate index '1' is out of range: none is defined");
    expectError(errorParsing("v 1e39 0 0\n"), 1, 1, "vertex coordinates must be finite");
    expectError(errorParsing("vn 0 1e60 0\n"), 1, 1, "normal components must be finite");
    expectError(errorParsing("vt 0 1e50\n"), 1, 1, "texture coordinates must be finite");
    expectError(errorParsing(tri + "f 1 2\n"), 4, 3, "at least 3 vertices, got 2");
}

TEST(ObjErrors, MaterialValuesMustBeFinite) {
    const std::string mtl = "# lib\nnewmtl ok\nKd 1 1 1\nnewmtl bad\nKd 1 1e99 1\n";
    Diagnostic d = errorParsing("mtllib lib.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", &mtl);
    EXPECT_EQ(d.loc.file, "lib.mtl");
    expectError(d, 4, 1, "material 'bad' has a value that is not a finite number");
}

TEST(ObjErrors, MeshTooLargeForTheMemoryGiven) {
    std::string text;
    for (int i = 0; i < 1000; ++i) text += "v 0 0 0\nf 1 1 1\n";
    Diagnostic d = errorParsing(text, nullptr, LoadLimits{4096});
    EXPECT_EQ(d.loc.line, 0);
    EXPECT_THAT(d.message, HasSubstr("the mesh needs about"));
    EXPECT_THAT(d.message, HasSubstr("1000 triangles"));
}

TEST(ObjWarnings, MixedCornersZeroNormalsAndAMissingLastLineBreak) {
    std::vector<Diagnostic> warnings;
    MeshData mesh =
        parse("v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 0\nvn 0 0 1\nf 1//2 2 3//2\nf 1//1 2//1 3//1",
              &warnings);
    ASSERT_EQ(warnings.size(), 3u);
    EXPECT_EQ(warnings[0].loc.line, 4);
    EXPECT_THAT(warnings[0].message, HasSubstr("normal has zero length"));
    EXPECT_EQ(warnings[1].loc.line, 6);
    EXPECT_THAT(warnings[1].message, HasSubstr("some corners only"));
    EXPECT_EQ(warnings[2].loc.line, 7);
    EXPECT_THAT(warnings[2].message, HasSubstr("may be truncated"));
    EXPECT_EQ(mesh.triangles[0].corners[0].normal, MeshData::kNone);
    EXPECT_EQ(mesh.normalTriangles, 1u);
}

TEST(ObjWarnings, NoFileIsReadWhenReadingFilesIsOff) {
    std::vector<Diagnostic> warnings;
    ObjOptions options;
    options.limits.readFiles = false;
    std::string text = "mtllib textured.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    MeshData mesh = parseObj(text, meshPath("x.obj"), warnings, options);
    EXPECT_TRUE(mesh.materials.empty());
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_THAT(warnings[0].message, HasSubstr("not read"));
}

}  // namespace
}  // namespace glint
