// An OBJ file's material libraries as other viewers treat them: a library that cannot be read
// is a warning and its faces take the default material; tinyobjloader's own remarks reach the
// user as Glint's warnings, at their line where they name one.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "glint/io/obj/obj_loader.h"

namespace glint {
namespace {

using ::testing::ElementsAre;

const std::string kTriangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";

std::string meshPath(const std::string& name) {
    return std::string(GLINT_TEST_DATA_DIR) + "/meshes/" + name;
}

std::vector<std::string> formatted(const std::vector<Diagnostic>& warnings) {
    std::vector<std::string> out;
    for (const Diagnostic& d : warnings) out.push_back(d.format("warning"));
    return out;
}

TEST(ObjLibraries, AMissingLibraryIsAWarningAndItsFacesTakeTheDefault) {
    std::vector<Diagnostic> warnings;
    MeshData mesh = loadObj(meshPath("missing-mtl.obj"), warnings);
    ASSERT_EQ(mesh.triangles.size(), 1u);
    EXPECT_EQ(mesh.triangles[0].material, MeshData::kNone);
    EXPECT_TRUE(mesh.materials.empty());
    const std::string path = meshPath("missing-mtl.obj");
    EXPECT_THAT(formatted(warnings),
                ElementsAre(path + ":1:8: warning: cannot read material library 'nowhere.mtl' (" +
                            meshPath("nowhere.mtl") +
                            "): No such file or directory; faces that use its materials take the "
                            "default material"));
}

TEST(ObjLibraries, TheMaterialsOfAMissingLibraryAreNotWarnedAboutAgain) {
    std::vector<Diagnostic> warnings;
    const std::string text =
        "mtllib gone.mtl\n" + kTriangle + "usemtl wood\nf 1 2 3\nusemtl stone\nf 1 2 3\n";
    MeshData mesh = parseObj(text, meshPath("x.obj"), warnings);
    EXPECT_EQ(mesh.triangles.size(), 2u);
    ASSERT_EQ(warnings.size(), 1u);  // the library, not 'wood' and 'stone'
    EXPECT_EQ(warnings[0].loc.line, 1);
    EXPECT_THAT(warnings[0].message, ::testing::StartsWith("cannot read material library"));
}

TEST(ObjLibraries, ADirectoryNamedAsALibraryIsAWarningToo) {
    std::vector<Diagnostic> warnings;
    parseObj("mtllib .\n" + kTriangle + "f 1 2 3\n", meshPath("x.obj"), warnings);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_THAT(warnings[0].message, ::testing::HasSubstr("cannot read material library '.'"));
}

TEST(ObjLibraries, TinyobjloadersRemarksAreWarningsAtTheirLine) {
    // tinyobjloader notes a material with both d and Tr, at its line of the library.
    const std::string mtl = "newmtl veil\nKd 1 1 1\nd 0.5\nTr 0.2\n";
    std::vector<Diagnostic> warnings;
    ObjOptions options;
    options.mtlText = &mtl;
    MeshData mesh = parseObj("mtllib veil.mtl\n" + kTriangle + "usemtl veil\nf 1 2 3\n", "m.obj",
                             warnings, options);
    EXPECT_EQ(mesh.triangles[0].material, 0u);
    EXPECT_THAT(formatted(warnings),
                ElementsAre("veil.mtl:4:1: warning: material 'veil' has both d and Tr: d is used"));
}

}  // namespace
}  // namespace glint
