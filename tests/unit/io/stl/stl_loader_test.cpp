// The STL reader (io/stl/stl_loader.h): ASCII and binary files, a binary file whose header
// starts with "solid", and every error with the file and where in it. The files are written by
// the tests themselves.

#include "glint/io/stl/stl_loader.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "glint/io/registry.h"
#include "unit/test_support.h"

namespace glint {
namespace {

using test::expectNear;
using ::testing::HasSubstr;

using Tri = std::array<std::array<float, 3>, 3>;

// Two triangles of a unit square in z = 0 (counter-clockwise seen from +z), and one in x = 0.
const std::vector<Tri> kTriangles = {
    {{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}}},
    {{{0, 0, 0}, {1, 1, 0}, {0, 1, 0}}},
    {{{0, 0, 0}, {0, 0, 1}, {0, 1, 1.5f}}},
};

/// A binary STL of `tris` whose 80-byte header is `header` (padded with spaces).
std::string binaryStl(const std::vector<Tri>& tris, std::string header = "binary by the test") {
    std::string s = header;
    s.resize(80, ' ');
    auto u32 = [&](uint32_t v) {
        for (int i = 0; i < 4; ++i) s.push_back(static_cast<char>(v >> (8 * i) & 0xFF));
    };
    auto f32 = [&](float f) {
        uint32_t v;
        std::memcpy(&v, &f, 4);
        u32(v);
    };
    u32(static_cast<uint32_t>(tris.size()));
    for (const Tri& t : tris) {
        for (int i = 0; i < 3; ++i) f32(0);  // the facet normal: not read
        for (const auto& p : t)
            for (float c : p) f32(c);
        s.append("\x07\x00", 2);  // attribute bytes
    }
    return s;
}

std::string asciiStl(const std::vector<Tri>& tris) {
    std::string s = "solid test part\n";
    for (const Tri& t : tris) {
        s += "  facet normal 0 0 1\n    outer loop\n";
        for (const auto& p : t) {
            char line[100];
            std::snprintf(line, sizeof line, "      vertex %g %g %g\n", p[0], p[1], p[2]);
            s += line;
        }
        s += "    endloop\n  endfacet\n";
    }
    return s + "endsolid test part\n";
}

MeshData parse(const std::string& bytes, std::vector<Diagnostic>* warningsOut = nullptr) {
    std::vector<Diagnostic> warnings;
    MeshData mesh = parseStl(bytes, "p.stl", warnings);
    if (warningsOut)
        *warningsOut = warnings;
    else
        EXPECT_TRUE(warnings.empty()) << warnings.front().format("warning");
    return mesh;
}

Diagnostic error(const std::string& bytes, const StlOptions& options = {}) {
    std::vector<Diagnostic> warnings;
    try {
        parseStl(bytes, "p.stl", warnings, options);
    } catch (const SceneError& e) {
        return e.diagnostic();
    }
    ADD_FAILURE() << "no SceneError";
    return {};
}

void expectTriangles(const MeshData& m, const std::vector<Tri>& tris) {
    ASSERT_EQ(m.triangles.size(), tris.size());
    ASSERT_EQ(m.positions.size(), 3 * tris.size());
    for (size_t t = 0; t < tris.size(); ++t)
        for (size_t k = 0; k < 3; ++k) {
            const MeshData::Corner& c = m.triangles[t].corners[k];
            const auto& p = tris[t][k];
            expectNear(Vec3(m.positions[c.position]), {p[0], p[1], p[2]});
            EXPECT_EQ(c.normal, MeshData::kNone);
            EXPECT_EQ(c.uv, MeshData::kNone);
        }
    EXPECT_TRUE(m.normals.empty());
    EXPECT_EQ(m.normalTriangles, 0u);
    EXPECT_EQ(m.name, "p.stl");
}

TEST(StlLoader, Binary) { expectTriangles(parse(binaryStl(kTriangles)), kTriangles); }

TEST(StlLoader, Ascii) { expectTriangles(parse(asciiStl(kTriangles)), kTriangles); }

TEST(StlLoader, ABinaryFileWhoseHeaderStartsWithSolidIsBinary) {
    // Some exporters write "solid <name>" into the binary header.
    expectTriangles(parse(binaryStl(kTriangles, "solid part exported as binary")), kTriangles);
    // Even cut short, it is not read as text: the error is the binary one.
    std::string cut = binaryStl(kTriangles, "solid part");
    cut.resize(cut.size() - 10);
    EXPECT_THAT(error(cut).message,
                HasSubstr("the binary STL header announces 3 triangles (234 bytes), but the file "
                          "has 224 bytes: is it complete?"));
}

TEST(StlLoader, AsciiKeywordsInAnyCaseSeveralSolidsAndPolygons) {
    std::string text =
        "SOLID upper\r\nFACET NORMAL 0 0 0\r\nOUTER LOOP\r\nVERTEX 0 0 0\r\nVERTEX 1 0 0\r\n"
        "VERTEX 1 1 0\r\nENDLOOP\r\nENDFACET\r\nENDSOLID upper\r\n"
        "solid second\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
        "vertex 1 1 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid";
    std::vector<Diagnostic> warnings;
    MeshData m = parse(text, &warnings);
    ASSERT_EQ(m.triangles.size(), 3u);
    expectNear(Vec3(m.positions[m.triangles[2].corners[2].position]), {0, 1, 0});
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_EQ(warnings[0].message, "1 facets have more than 3 vertices: they are split as fans");
}

TEST(StlLoader, TrailingBytesAfterABinaryFileAreAWarning) {
    std::vector<Diagnostic> warnings;
    MeshData m = parse(binaryStl(kTriangles) + "junk", &warnings);
    expectTriangles(m, kTriangles);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_EQ(warnings[0].message,
              "4 bytes follow the last of the 3 triangles the header announces: they are ignored");
}

// ---- Errors ----

TEST(StlErrors, AsciiErrorsNameTheLineAndColumn) {
    std::string text = asciiStl(kTriangles);
    std::string bad = text;
    bad.replace(bad.find("vertex 1 0 0"), 12, "vertex 1 x 0");
    Diagnostic d = error(bad);
    EXPECT_EQ(d.loc.file, "p.stl");
    EXPECT_EQ(d.loc.line, 5);
    EXPECT_EQ(d.loc.column, 16);
    EXPECT_EQ(d.message, "'x' is not a number");

    d = error(
        "solid a\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\n"
        "endfacet\nendsolid a\n");
    EXPECT_EQ(d.loc.line, 2);
    EXPECT_EQ(d.message, "a facet needs 3 vertices, got 2");

    d = error("solid a\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n");
    EXPECT_EQ(d.message,
              "the file ends where 'endloop' (after a facet's vertices) should be: is "
              "it complete?");

    d = error(
        "solid a\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 "
        "1e39\nendloop\nendfacet\n");
    EXPECT_EQ(d.loc.line, 6);
    EXPECT_EQ(d.message, "'1e39': coordinates must be finite numbers (at most about 3.4e38)");

    d = error("solid a\nfacets normal 0 0 1\n");
    EXPECT_EQ(d.message, "'facets' where 'facet' or 'endsolid' should be");
    EXPECT_EQ(error("solid a\nendsolid a\n").message, "the STL file has no facets");
}

TEST(StlErrors, BinaryErrors) {
    std::string bin = binaryStl(kTriangles);
    float inf = std::numeric_limits<float>::infinity();
    std::memcpy(&bin[84 + 50 + 12 + 12 + 4], &inf, 4);  // triangle 1, corner 1, y
    EXPECT_EQ(error(bin).message,
              "triangle 1 (byte 158): vertex coordinates must be finite numbers");
    EXPECT_EQ(error(std::string(40, '\1')).message,
              "not an STL file: too short for a binary one (40 bytes, at least 84) and not text "
              "starting with 'solid'");
    EXPECT_EQ(error(binaryStl({})).message, "the binary STL file has no triangles");
    // A header that claims 4 billion triangles in a 90-byte file allocates nothing.
    std::string huge = binaryStl({});
    huge[80] = huge[81] = huge[82] = huge[83] = '\xff';
    EXPECT_THAT(error(huge + "123456").message,
                HasSubstr("announces 4294967295 triangles (214748364834 bytes), but the file has "
                          "90 bytes"));
    StlOptions small;
    small.limits.memoryBytes = 1000;
    EXPECT_THAT(error(binaryStl(kTriangles), small).message, HasSubstr("the mesh needs about"));
}

class StlFiles : public test::TempDirTest {};

TEST_F(StlFiles, TheRegistryReadsBothKindsAndErrorsNameTheFile) {
    std::ofstream(path("a.stl"), std::ios::binary) << asciiStl(kTriangles);
    std::ofstream(path("b.stl"), std::ios::binary) << binaryStl(kTriangles, "solid b");
    std::vector<Diagnostic> warnings;
    EXPECT_EQ(loadModel(path("a.stl"), warnings).triangles(), 3u);
    EXPECT_EQ(loadModel(path("b.stl"), warnings).triangles(), 3u);
    EXPECT_TRUE(warnings.empty());
    std::string cut = binaryStl(kTriangles);
    std::ofstream(path("cut.stl"), std::ios::binary) << cut.substr(0, 150);
    try {
        loadModel(path("cut.stl"), warnings);
        FAIL() << "no SceneError";
    } catch (const SceneError& e) {
        EXPECT_EQ(e.diagnostic().loc.file, path("cut.stl"));
        EXPECT_THAT(e.diagnostic().message, HasSubstr("is it complete?"));
    }
}

}  // namespace
}  // namespace glint
