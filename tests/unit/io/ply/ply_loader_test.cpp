// The PLY reader (io/ply/ply_loader.h): ASCII and binary files of both byte orders with
// normals, colours and texture coordinates, the Stanford scans' layout, polygons, strips, and
// every error with the file and where in it. The files are written by the tests themselves.

#include "glint/io/ply/ply_loader.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "glint/io/registry.h"
#include "glint/render/renderer.h"
#include "unit/test_support.h"

namespace glint {
namespace {

using test::expectNear;
using ::testing::HasSubstr;
using namespace std::string_literals;

/// Values appended to a binary PLY body in either byte order.
struct Bin {
    bool big = false;
    std::string bytes;
    template <typename T>
    Bin& put(T v) {
        char b[sizeof(T)];
        std::memcpy(b, &v, sizeof(T));
        if (big) std::reverse(b, b + sizeof(T));
        bytes.append(b, sizeof(T));
        return *this;
    }
};

double srgbDecoded(double byte) {
    double c = byte / 255;
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

// A unit quad (vertices 0-3) and a triangle (1, 4, 2), with normals (vertex 0's not of unit
// length), byte colours and texture coordinates.
const char* kHeaderBody =
    "comment written by the test\n"
    "element vertex 5\n"
    "property float x\nproperty float y\nproperty float z\n"
    "property float nx\nproperty float ny\nproperty float nz\n"
    "property uchar red\nproperty uchar green\nproperty uchar blue\n"
    "property float s\nproperty float t\n"
    "element face 2\n"
    "property list uchar int vertex_indices\n"
    "end_header\n";

struct V {
    float x, y, z, nx, ny, nz;
    uint8_t r, g, b;
    float s, t;
};
const V kVertices[] = {
    {0, 0, 0, 0, 0, 2, 255, 0, 0, 0, 0},         {1, 0, 0, 0, 0, 1, 0, 255, 0, 1, 0},
    {1, 1, 0, 0, 0, 1, 0, 0, 255, 1, 1},         {0, 1, 0, 0, 0, 1, 128, 128, 128, 0, 1},
    {2, 0, 0, 0, 0, 1, 10, 20, 30, 0.5f, 0.25f},
};
const std::vector<std::vector<int>> kFaces = {{0, 1, 2, 3}, {1, 4, 2}};

std::string asciiPly() {
    std::string s = "ply\nformat ascii 1.0\n"s + kHeaderBody;
    for (const V& v : kVertices) {
        char line[200];
        std::snprintf(line, sizeof line, "%g %g %g %g %g %g %d %d %d %g %g\n", v.x, v.y, v.z, v.nx,
                      v.ny, v.nz, v.r, v.g, v.b, v.s, v.t);
        s += line;
    }
    for (const auto& f : kFaces) {
        s += std::to_string(f.size());
        for (int i : f) s.append(" ").append(std::to_string(i));
        s += "\n";
    }
    return s;
}

std::string binaryPly(bool big) {
    Bin b{big, "ply\nformat "s + (big ? "binary_big_endian" : "binary_little_endian") + " 1.0\n" +
                   kHeaderBody};
    for (const V& v : kVertices)
        b.put(v.x)
            .put(v.y)
            .put(v.z)
            .put(v.nx)
            .put(v.ny)
            .put(v.nz)
            .put(v.r)
            .put(v.g)
            .put(v.b)
            .put(v.s)
            .put(v.t);
    for (const auto& f : kFaces) {
        b.put(static_cast<uint8_t>(f.size()));
        for (int i : f) b.put(static_cast<int32_t>(i));
    }
    return b.bytes;
}

MeshData parse(const std::string& bytes, std::vector<Diagnostic>* warningsOut = nullptr,
               const PlyOptions& options = {}) {
    std::vector<Diagnostic> warnings;
    MeshData mesh = parsePly(bytes, "m.ply", warnings, options);
    if (warningsOut)
        *warningsOut = warnings;
    else
        EXPECT_TRUE(warnings.empty()) << warnings.front().format("warning");
    return mesh;
}

Diagnostic error(const std::string& bytes, const PlyOptions& options = {}) {
    std::vector<Diagnostic> warnings;
    try {
        parsePly(bytes, "m.ply", warnings, options);
    } catch (const SceneError& e) {
        return e.diagnostic();
    }
    ADD_FAILURE() << "no SceneError";
    return {};
}

void expectTheTestMesh(const MeshData& m) {
    ASSERT_EQ(m.positions.size(), 5u);
    ASSERT_EQ(m.normals.size(), 5u);
    ASSERT_EQ(m.colors.size(), 5u);
    ASSERT_EQ(m.uvs.size(), 5u);
    for (size_t i = 0; i < 5; ++i) {
        const V& v = kVertices[i];
        expectNear(Vec3(m.positions[i]), {v.x, v.y, v.z});
        EXPECT_FLOAT_EQ(m.uvs[i][0], v.s);
        EXPECT_FLOAT_EQ(m.uvs[i][1], v.t);
        EXPECT_NEAR(m.colors[i][0], srgbDecoded(v.r), 1e-6) << i;
        EXPECT_NEAR(m.colors[i][1], srgbDecoded(v.g), 1e-6) << i;
        EXPECT_NEAR(m.colors[i][2], srgbDecoded(v.b), 1e-6) << i;
        EXPECT_EQ(m.colors[i][3], 1.0f);
    }
    expectNear(Vec3(m.normals[0]), {0, 0, 1});  // normalised
    // The quad as a fan from its first corner, then the triangle; every corner refers to its
    // vertex for each attribute.
    ASSERT_EQ(m.triangles.size(), 3u);
    const int expected[3][3] = {{0, 1, 2}, {0, 2, 3}, {1, 4, 2}};
    for (size_t t = 0; t < 3; ++t)
        for (size_t k = 0; k < 3; ++k) {
            const MeshData::Corner& c = m.triangles[t].corners[k];
            EXPECT_EQ(c.position, uint32_t(expected[t][k]));
            EXPECT_EQ(c.normal, c.position);
            EXPECT_EQ(c.uv, c.position);
            EXPECT_EQ(c.color, c.position);
            EXPECT_EQ(c.uv1, MeshData::kNone);
            EXPECT_EQ(m.triangles[t].material, MeshData::kNone);
        }
    EXPECT_EQ(m.normalTriangles, 3u);
    EXPECT_EQ(m.uvTriangles, 3u);
    EXPECT_EQ(m.name, "m.ply");
}

TEST(PlyLoader, AsciiWithNormalsColoursAndTextureCoordinates) {
    expectTheTestMesh(parse(asciiPly()));
}

TEST(PlyLoader, BinaryLittleEndian) { expectTheTestMesh(parse(binaryPly(false))); }

TEST(PlyLoader, BinaryBigEndian) { expectTheTestMesh(parse(binaryPly(true))); }

TEST(PlyLoader, WindowsLineEndsInTheHeader) {
    std::string text = asciiPly();
    std::string crlf;
    for (char c : text) crlf += c == '\n' ? "\r\n"s : std::string(1, c);
    expectTheTestMesh(parse(crlf));
    // A binary body starts right after end_header's line break, whatever it is.
    std::string bin = binaryPly(false);
    size_t at = bin.find("end_header\n") + 10;
    bin.insert(at, "\r");
    expectTheTestMesh(parse(bin));
}

/// The layout of the Stanford scans (bun_zipper.ply and the like): extra vertex properties,
/// and faces as `list uchar int vertex_indices`.
TEST(PlyLoader, StanfordScanLayoutSkipsWhatItDoesNotUse) {
    Bin b{false,
          "ply\nformat binary_little_endian 1.0\ncomment zipper output\n"
          "element vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
          "property float confidence\nproperty float intensity\n"
          "element face 2\nproperty list uchar int vertex_indices\nend_header\n"};
    const float p[4][3] = {{-0.0378f, 0.128f, 0.00338f},
                           {-0.0447f, 0.128f, 0.00153f},
                           {-0.0687f, 0.151f, 0.0377f},
                           {-0.06f, 0.152f, 0.0410f}};
    for (const auto& v : p) b.put(v[0]).put(v[1]).put(v[2]).put(0.9f).put(0.5f);
    b.put(uint8_t(3)).put(int32_t(0)).put(int32_t(1)).put(int32_t(2));
    b.put(uint8_t(3)).put(int32_t(0)).put(int32_t(2)).put(int32_t(3));
    MeshData m = parse(b.bytes);
    ASSERT_EQ(m.positions.size(), 4u);
    expectNear(Vec3(m.positions[2]), Vec3(Vec3f(p[2][0], p[2][1], p[2][2])));
    EXPECT_TRUE(m.normals.empty());
    EXPECT_TRUE(m.colors.empty());
    EXPECT_TRUE(m.uvs.empty());
    ASSERT_EQ(m.triangles.size(), 2u);
    EXPECT_EQ(m.triangles[1].corners[2].position, 3u);
    EXPECT_EQ(m.triangles[1].corners[2].normal, MeshData::kNone);
    EXPECT_EQ(m.normalTriangles, 0u);
}

TEST(PlyLoader, OtherTypesNamesAndElementsAreRead) {
    // Double positions, `vertex_index` with a ushort count and uint indices, an element of
    // lists before the faces (skipped record by record), float colours with alpha (sRGB
    // decoded, alpha as it is), u/v coordinates.
    Bin b{true,
          "ply\nformat binary_big_endian 1.0\n"
          "element vertex 3\nproperty double x\nproperty double y\nproperty double z\n"
          "property float red\nproperty float green\nproperty float blue\nproperty float alpha\n"
          "property double u\nproperty double v\n"
          "element material 2\nproperty list int float parameters\nproperty uchar flag\n"
          "element face 1\nproperty uchar flags\nproperty list ushort uint vertex_index\n"
          "end_header\n"};
    b.put(0.0).put(0.0).put(0.0).put(1.0f).put(0.5f).put(0.0f).put(0.25f).put(0.0).put(0.0);
    b.put(1.0).put(0.0).put(0.0).put(0.0f).put(0.0f).put(1.0f).put(1.0f).put(1.0).put(0.0);
    b.put(0.0).put(1.0).put(0.0).put(2.0f).put(-1.0f).put(0.0f).put(0.5f).put(0.0).put(1.0);
    b.put(int32_t(2)).put(1.5f).put(2.5f).put(uint8_t(7));
    b.put(int32_t(0)).put(uint8_t(8));
    b.put(uint8_t(1)).put(uint16_t(3)).put(uint32_t(2)).put(uint32_t(1)).put(uint32_t(0));
    MeshData m = parse(b.bytes);
    ASSERT_EQ(m.positions.size(), 3u);
    expectNear(Vec3(m.positions[2]), {0, 1, 0});
    ASSERT_EQ(m.colors.size(), 3u);
    EXPECT_FLOAT_EQ(m.colors[0][0], 1.0f);
    EXPECT_NEAR(m.colors[0][1], srgbDecoded(127.5), 1e-6);
    EXPECT_FLOAT_EQ(m.colors[0][3], 0.25f);  // alpha is linear
    EXPECT_FLOAT_EQ(m.colors[2][0], 1.0f);   // clamped to [0, 1]
    EXPECT_FLOAT_EQ(m.colors[2][1], 0.0f);
    ASSERT_EQ(m.uvs.size(), 3u);
    EXPECT_FLOAT_EQ(m.uvs[2][1], 1.0f);
    ASSERT_EQ(m.triangles.size(), 1u);
    EXPECT_EQ(m.triangles[0].corners[0].position, 2u);
    EXPECT_EQ(m.triangles[0].corners[2].position, 0u);
}

TEST(PlyLoader, FaceColoursAndPerCornerTextureCoordinates) {
    // MeshLab writes per-corner coordinates as a face list `texcoord` (u0 v0 u1 v1 ...), and
    // some files colour faces rather than vertices.
    std::string text =
        "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
        "property float z\nelement face 2\nproperty list uchar int vertex_indices\n"
        "property list uchar float texcoord\nproperty uchar red\nproperty uchar green\n"
        "property uchar blue\nend_header\n"
        "0 0 0\n1 0 0\n1 1 0\n0 1 0\n"
        "3 0 1 2 6 0 0 1 0 1 1 255 0 0\n"
        "3 0 2 3 6 0.1 0.1 0.9 0.9 0.1 0.9 0 0 255\n";
    MeshData m = parse(text);
    ASSERT_EQ(m.triangles.size(), 2u);
    ASSERT_EQ(m.colors.size(), 2u);
    EXPECT_EQ(m.triangles[1].corners[0].color, 1u);
    EXPECT_EQ(m.triangles[1].corners[2].color, 1u);
    EXPECT_FLOAT_EQ(m.colors[1][2], 1.0f);
    EXPECT_FLOAT_EQ(m.colors[1][0], 0.0f);
    ASSERT_EQ(m.uvs.size(), 6u);
    const MeshData::Corner& c = m.triangles[1].corners[1];
    EXPECT_FLOAT_EQ(m.uvs[c.uv][0], 0.9f);
    EXPECT_FLOAT_EQ(m.uvs[c.uv][1], 0.9f);
    EXPECT_EQ(m.uvTriangles, 2u);
}

TEST(PlyLoader, PolygonsAreFans) {
    std::string text =
        "ply\nformat ascii 1.0\nelement vertex 6\nproperty float x\nproperty float y\n"
        "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
        "0 0 0\n1 0 0\n2 1 0\n1 2 0\n0 2 0\n-1 1 0\n"
        "6 0 1 2 3 4 5\n";
    MeshData m = parse(text);
    ASSERT_EQ(m.triangles.size(), 4u);
    for (size_t t = 0; t < 4; ++t) {
        EXPECT_EQ(m.triangles[t].corners[0].position, 0u);
        EXPECT_EQ(m.triangles[t].corners[1].position, t + 1);
        EXPECT_EQ(m.triangles[t].corners[2].position, t + 2);
    }
}

TEST(PlyLoader, TriangleStripsWithRestarts) {
    // The Stanford tools' `tristrips`: -1 ends a strip; every other triangle turns back.
    std::string text =
        "ply\nformat ascii 1.0\nelement vertex 6\nproperty float x\nproperty float y\n"
        "property float z\nelement tristrips 1\nproperty list int int vertex_indices\n"
        "end_header\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n5 5 0\n6 5 0\n"
        "8 0 1 2 3 -1 3 4 5\n";
    MeshData m = parse(text);
    ASSERT_EQ(m.triangles.size(), 3u);
    auto tri = [&](size_t t) {
        const auto& c = m.triangles[t].corners;
        return std::vector<uint32_t>{c[0].position, c[1].position, c[2].position};
    };
    EXPECT_EQ(tri(0), (std::vector<uint32_t>{0, 1, 2}));
    EXPECT_EQ(tri(1), (std::vector<uint32_t>{2, 1, 3}));
    EXPECT_EQ(tri(2), (std::vector<uint32_t>{3, 4, 5}));
}

TEST(PlyLoader, WarnsOfShortFacesZeroNormalsAndTrailingBytes) {
    std::string text =
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
        "property float z\nproperty float nx\nproperty float ny\nproperty float nz\n"
        "element face 3\nproperty list uchar int vertex_indices\nend_header\n"
        "0 0 0 0 0 0\n1 0 0 0 0 1\n0 1 0 0 0 1\n3 0 1 2\n2 0 1\n0\n";
    std::vector<Diagnostic> warnings;
    MeshData m = parse(text + "extra\n", &warnings);
    EXPECT_EQ(m.triangles.size(), 1u);
    expectNear(Vec3(m.normals[0]), {0, 0, 0});
    ASSERT_EQ(warnings.size(), 3u);
    EXPECT_EQ(warnings[0].message, "2 faces have fewer than 3 vertices: they are skipped");
    EXPECT_THAT(warnings[1].message, HasSubstr("1 vertex normals have zero length"));
    EXPECT_EQ(warnings[2].format("warning"),
              "m.ply:19:1: warning: 6 bytes follow the last element: they are ignored");
}

// ---- Errors ----

void expectError(const Diagnostic& d, int line, int column, const std::string& message) {
    EXPECT_EQ(d.loc.file, "m.ply");
    EXPECT_EQ(d.loc.line, line);
    EXPECT_EQ(d.loc.column, column);
    EXPECT_EQ(d.message, message);
}

TEST(PlyErrors, HeaderErrorsNameTheLineAndColumn) {
    expectError(error("ply\nformat ascii 1.0\nelement vertex 1\nproperty real x\n"), 4, 10,
                "unknown PLY type 'real' (char, uchar, short, ushort, int, uint, float, double, "
                "or int8 to float64)");
    expectError(error("ply\nformat ascii 2.0\n"), 2, 14,
                "PLY version '2.0' is not 1.0, the only one");
    expectError(error("ply\nformat ascii 1.0\nelement vertex many\n"), 3, 16,
                "element count 'many' is not a whole number of at most 2^64 - 1");
    expectError(error("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"), 4, 0,
                "the PLY header has no 'end_header' line: is the file complete?");
    expectError(error("ply\nformat ascii 1.0\nvertex 1\n"), 3, 1,
                "unknown PLY header line 'vertex' (format, element, property, comment, obj_info "
                "or end_header)");
    expectError(error("ply\nproperty float x\nend_header\n"), 2, 1,
                "'property' before any 'element'");
}

TEST(PlyErrors, MissingElementsAndProperties) {
    const std::string start = "ply\nformat ascii 1.0\n";
    expectError(error(start + "element vertex 1\nproperty float x\nproperty float y\n"
                              "element face 0\nend_header\n0 0\n"),
                3, 0, "element 'vertex' needs properties 'x', 'y' and 'z' (scalars)");
    Diagnostic pointCloud = error(start +
                                  "element vertex 1\nproperty float x\nproperty float y\n"
                                  "property float z\nend_header\n0 0 0\n");
    EXPECT_EQ(pointCloud.message,
              "the file has no faces (element 'face'): it is a point cloud, and Glint renders "
              "surfaces");
    expectError(error(start + "element vertex 1\nproperty float x\nproperty float y\n"
                              "property float z\nelement face 1\nproperty int vertex_indices\n"
                              "end_header\n0 0 0\n1\n"),
                7, 0,
                "element 'face': property 'vertex_indices' must be a list of integers ('property "
                "list uchar int vertex_indices')");
}

const std::string kTriangleHeader =
    "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
    "element face 1\nproperty list uchar int vertex_indices\nend_header\n";

TEST(PlyErrors, AsciiDataErrorsNameTheLineAndColumn) {
    const std::string start = "ply\nformat ascii 1.0\n" + kTriangleHeader;
    expectError(error(start + "0 0 0\n1 0 0\n0 1 zero\n3 0 1 2\n"), 12, 5,
                "vertex 2: 'zero' is not a number");
    expectError(error(start + "0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n"), 13, 7,
                "face 0: vertex index 3 is out of range: the file has 3 vertices (0 to 3 - 1)");
    expectError(error(start + "0 0 0\n1 0 0\n0 1 0\n3 0 1 -2\n"), 13, 7,
                "face 0: vertex index -2 is out of range: the file has 3 vertices (0 to 3 - 1)");
    expectError(error(start + "0 0 0\n1 0 0\n0 1e39 0\n3 0 1 2\n"), 12, 8,
                "vertex 2: vertex coordinates must be finite numbers (at most about 3.4e38)");
    expectError(error(start + "0 0 0\n1 0 0\n0 1 0\n3 0 1.5 2\n"), 13, 5,
                "face 0: '1.5' is not a whole number");
    Diagnostic cut = error(start + "0 0 0\n1 0 0\n0 1 0\n3 0 1");
    EXPECT_EQ(cut.message, "the file ends in face 0 of 1: is it complete?");
    EXPECT_EQ(cut.loc.line, 13);
}

TEST(PlyErrors, TruncatedBinaryFilesNameTheRecordAndByte) {
    std::string bin = binaryPly(false);
    const size_t body = bin.find("end_header\n") + 11;
    // Cut in the middle of the last face (a triangle: 1 + 3 x 4 bytes).
    Diagnostic d = error(bin.substr(0, bin.size() - 5));
    EXPECT_EQ(d.loc.file, "m.ply");
    EXPECT_EQ(d.loc.line, 0);
    EXPECT_EQ(d.message, "the file ends in face 1 of 2 (byte " + std::to_string(bin.size() - 12) +
                             "): is it complete?");
    // Cut in the vertices: found before anything is read or allocated.
    d = error(bin.substr(0, body + 10));
    EXPECT_EQ(d.message, "the file ends in vertex 0 of 5 (byte " + std::to_string(body) +
                             "): is it complete?");
}

TEST(PlyErrors, HugeCountsInATinyFileAllocateNothing) {
    // 20 bytes of data that claim 4 billion vertices and faces: refused from the sizes alone.
    std::string head =
        "ply\nformat binary_little_endian 1.0\nelement vertex 4294967294\n"
        "property float x\nproperty float y\nproperty float z\n"
        "element face 4000000000\nproperty list uchar int vertex_indices\n"
        "end_header\n";
    Diagnostic d = error(head + std::string(20, '\1'));
    EXPECT_THAT(d.message, HasSubstr("the file ends in vertex 1 of 4294967294"));
    // A list count beyond the bytes left.
    Bin b{false, "ply\nformat binary_little_endian 1.0\n" + kTriangleHeader};
    for (int i = 0; i < 9; ++i) b.put(0.5f * float(i % 3));
    b.put(uint8_t(200)).put(int32_t(0));
    EXPECT_EQ(error(b.bytes).message, "the file ends in face 0 of 1 (byte " +
                                          std::to_string(b.bytes.size() - 4) +
                                          "): is it complete?");
    // ASCII: a value takes two bytes at least.
    d = error(
        "ply\nformat ascii 1.0\nelement vertex 1000000000\nproperty float x\n"
        "property float y\nproperty float z\nelement face 1\n"
        "property list uchar int vertex_indices\nend_header\n0 0 0\n");
    EXPECT_THAT(d.message,
                HasSubstr("the file is too short for the elements its header announces"));
}

TEST(PlyErrors, AMeshBeyondTheMemoryLimitIsRefusedBeforeReading) {
    PlyOptions options;
    options.limits.memoryBytes = 1000;
    Diagnostic d = error(binaryPly(false), options);
    EXPECT_THAT(d.message, HasSubstr("the mesh needs about"));
    EXPECT_THAT(d.message, HasSubstr("(3 triangles), more than the"));
}

TEST(PlyErrors, BinaryIndexOutOfRangeNamesTheFaceAndByte) {
    Bin b{false, "ply\nformat binary_little_endian 1.0\n" + kTriangleHeader};
    for (int i = 0; i < 9; ++i) b.put(float(i % 3 == i / 3));
    b.put(uint8_t(3)).put(int32_t(0)).put(int32_t(7)).put(int32_t(1));
    EXPECT_EQ(error(b.bytes).message,
              "face 0 (byte " + std::to_string(b.bytes.size() - 8) +
                  "): vertex index 7 is out of range: the file has 3 vertices (0 to 3 - 1)");
}

// ---- Files, the registry and rendering ----

class PlyFiles : public test::TempDirTest {};

TEST_F(PlyFiles, TheRegistryReadsPlyByMagicOrExtension) {
    std::ofstream(path("quad.ply"), std::ios::binary) << binaryPly(false);
    std::vector<Diagnostic> warnings;
    Model model = loadModel(path("quad.ply"), warnings);
    EXPECT_TRUE(warnings.empty());
    ASSERT_EQ(model.meshes.size(), 1u);
    MeshData m = std::move(model.meshes[0]);
    EXPECT_EQ(m.name, path("quad.ply"));
    m.name = "m.ply";
    expectTheTestMesh(m);
    // Named otherwise, it is still PLY (with a warning).
    std::ofstream(path("quad.obj"), std::ios::binary) << asciiPly();
    warnings.clear();
    EXPECT_EQ(loadModel(path("quad.obj"), warnings).triangles(), 3u);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_EQ(warnings[0].message, "the file is PLY, whatever its name says: it is read as PLY");
}

TEST_F(PlyFiles, ErrorsNameTheFile) {
    std::string bin = binaryPly(true);
    std::ofstream(path("cut.ply"), std::ios::binary) << bin.substr(0, bin.size() - 3);
    std::vector<Diagnostic> warnings;
    try {
        loadModel(path("cut.ply"), warnings);
        FAIL() << "no SceneError";
    } catch (const SceneError& e) {
        EXPECT_EQ(e.diagnostic().loc.file, path("cut.ply"));
        EXPECT_THAT(e.diagnostic().message, HasSubstr("the file ends in face 1 of 2"));
    }
}

TEST_F(PlyFiles, APlyModelRendersWhereItIs) {
    // The unit quad and its neighbour, framed as `glint quad.ply` frames it: the camera looks
    // at the mesh, so the image's centre sees it lit, and it is brighter there than the same
    // framing without the mesh's faces would be (they are light grey under two lights).
    std::ofstream(path("quad.ply"), std::ios::binary) << binaryPly(false);
    std::vector<Diagnostic> warnings;
    LoadOptions options;
    options.width = 48;
    options.height = 36;
    options.look = ModelLook::classic();  // lights and a floor: what this checks
    ModelScene m = loadSceneFile(path("quad.ply"), warnings, options);
    ASSERT_TRUE(m.scene);
    EXPECT_THAT(m.note, HasSubstr("quad.ply has no camera or lights"));
    EXPECT_EQ(m.scene->primitives.triangleCount(), 3u);
    m.scene->prepare();
    // A ray from the camera through the middle of the image hits the mesh (z = 0, within
    // x in [0, 2], y in [0, 1]) with the interpolated normal +z.
    const CameraSpec& cam = *m.scene->camera;
    auto si = test::shoot(*m.scene, cam.eye, cam.center - cam.eye);
    ASSERT_TRUE(si);
    EXPECT_NEAR(si->p.z, 0, 1e-6);
    EXPECT_GE(si->p.x, 0);
    EXPECT_LE(si->p.x, 2);
    expectNear(si->n, {0, 0, 1}, 1e-6);
    RenderOptions o;
    o.threads = 1;
    Film film = render(*m.scene, o).film;
    const Vec3& centre = film.at(24, 18);
    EXPECT_GT(centre.x, 0.2);
    EXPECT_GT(centre.y, 0.2);
    EXPECT_GT(centre.z, 0.2);
}

TEST_F(PlyFiles, ASceneFilePlacesAPlyMeshWithItsMaterial) {
    // `mesh quad.ply` under the current material: red where the mesh is, the black background
    // around it.
    std::ofstream(path("quad.ply"), std::ios::binary) << binaryPly(true);
    std::ofstream(path("s.test")) << "size 32 32\ncamera 1 0.5 3 1 0.5 0 0 1 0 45\n"
                                     "directional 0 0 1 1 1 1\ndiffuse 1 0 0\nmesh quad.ply\n";
    std::vector<Diagnostic> warnings;
    ModelScene m = loadSceneFile(path("s.test"), warnings);
    EXPECT_TRUE(warnings.empty());
    m.scene->prepare();
    RenderOptions o;
    o.threads = 1;
    Film film = render(*m.scene, o).film;
    // Pixel (10, 16) looks at (0.57, 0.5, 0), inside the quad; pixel (16, 2) above the mesh.
    const Vec3& inside = film.at(10, 16);
    EXPECT_GT(inside.x, 0.9);
    EXPECT_LT(inside.y, 0.3);
    expectNear(film.at(16, 2), Vec3(0));
}

TEST_F(PlyFiles, VertexColoursTintAPhysicallyBasedMaterialOnly) {
    // A unit quad whose vertices are all red: under `metallic 0` (a physically based material,
    // base colour white) the path tracer shows red; under the course's flat material the
    // colours are not used, as for a glTF primitive without a material (docs/scene-format.md).
    std::ofstream(path("red.ply")) << "ply\nformat ascii 1.0\nelement vertex 4\n"
                                      "property float x\nproperty float y\nproperty float z\n"
                                      "property uchar red\nproperty uchar green\n"
                                      "property uchar blue\nelement face 1\n"
                                      "property list uchar int vertex_indices\nend_header\n"
                                      "0 0 0 255 0 0\n2 0 0 255 0 0\n2 1 0 255 0 0\n"
                                      "0 1 0 255 0 0\n4 0 1 2 3\n";
    auto renderWith = [&](const std::string& material) {
        std::ofstream(path("s.test")) << "size 32 32\nintegrator path\nspp 4\n"
                                         "camera 1 0.5 3 1 0.5 0 0 1 0 45\n"
                                         "directional 0 1 1 1 1 1\ndiffuse 1 1 1\n" +
                                             material + "mesh red.ply\n";
        std::vector<Diagnostic> warnings;
        ModelScene m = loadSceneFile(path("s.test"), warnings);
        m.scene->prepare();
        // The hit has the colour, without vertex normals or texture coordinates.
        auto si = test::shoot(*m.scene, {1, 0.5, 3}, {0, 0, -1});
        EXPECT_TRUE(si && si->hasColor);
        if (si) expectNear(si->color, {1, 0, 0}, 1e-6);
        RenderOptions o;
        o.threads = 1;
        return render(*m.scene, o).film.at(16, 16);  // looks at (1, 0.5, 0), inside the quad
    };
    Vec3 pbr = renderWith("metallic 0\n");
    EXPECT_GT(pbr.x, 0.2);
    EXPECT_LT(pbr.y, 0.01 * pbr.x);
    EXPECT_LT(pbr.z, 0.01 * pbr.x);
    Vec3 flat = renderWith("");
    EXPECT_GT(flat.x, 0.2);
    EXPECT_NEAR(flat.y, flat.x, 1e-6 + 0.01 * flat.x);
}

}  // namespace
}  // namespace glint
