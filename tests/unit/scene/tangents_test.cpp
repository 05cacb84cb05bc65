// Generated tangents (scene/tangents.h): MikkTSpace's tangent and sign on flat layouts, plain
// and mirrored; a sphere's tangents along du and orthogonal to the normals; vertices split by
// handedness; the angle weighting; degenerate texture coordinates giving a fallback, not NaN.

#include "glint/scene/tangents.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>
#include <set>

#include "unit/test_support.h"

namespace glint {
namespace {

using test::expectNear;

/// Adds triangle (a, b, c) of vertex indices; the same index is used for position, normal
/// (when the mesh has normals) and uv.
void addTriangle(MeshData& m, uint32_t a, uint32_t b, uint32_t c, uint32_t material = 0) {
    MeshData::Triangle t;
    const uint32_t ids[3] = {a, b, c};
    for (size_t k = 0; k < 3; ++k) {
        t.corners[k].position = ids[k];
        if (!m.normals.empty()) t.corners[k].normal = ids[k];
        if (!m.uvs.empty()) t.corners[k].uv = ids[k];
        if (!m.uv1s.empty()) t.corners[k].uv1 = ids[k];
    }
    t.material = material;
    m.triangles.push_back(t);
}

/// The unit square in z = 0 facing +z, as two triangles, with texture coordinates uv(x, y).
MeshData square(const std::function<TexCoord(float, float)>& uv) {
    MeshData m;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    m.normals.assign(4, Vec3f(0, 0, 1));
    for (const Vec3f& p : m.positions) m.uvs.push_back(uv(p.x, p.y));
    addTriangle(m, 0, 1, 2);
    addTriangle(m, 0, 2, 3);
    return m;
}

Vec3 tangentAt(const MeshData& m, size_t triangle, size_t corner) {
    const auto& t = m.tangents[m.triangles[triangle].corners[corner].tangent];
    return {t[0], t[1], t[2]};
}

float signAt(const MeshData& m, size_t triangle, size_t corner) {
    return m.tangents[m.triangles[triangle].corners[corner].tangent][3];
}

/// Every corner of every triangle: a unit tangent orthogonal to the corner's normal, finite.
void expectOrthonormal(const MeshData& m, double eps = 1e-6) {
    for (size_t t = 0; t < m.triangles.size(); ++t)
        for (size_t k = 0; k < 3; ++k) {
            const MeshData::Corner& c = m.triangles[t].corners[k];
            ASSERT_NE(c.tangent, MeshData::kNone);
            Vec3 tangent = tangentAt(m, t, k);
            ASSERT_TRUE(isFinite(tangent));
            EXPECT_NEAR(length(tangent), 1, eps);
            if (c.normal != MeshData::kNone) {
                EXPECT_NEAR(dot(tangent, Vec3(m.normals[c.normal])), 0, eps);
            }
            float w = signAt(m, t, k);
            EXPECT_TRUE(w == 1 || w == -1) << w;
        }
}

TEST(Tangents, AFlatSquareHasTheTangentAlongUAndSignPlusOne) {
    MeshData m = square([](float x, float y) { return TexCoord{x, y}; });
    TangentReport r = generateTangents(m);
    EXPECT_EQ(r.triangles, 2u);
    EXPECT_EQ(r.tangents, 4u);  // one per vertex: the two triangles agree everywhere
    EXPECT_EQ(r.fallback, 0u);
    EXPECT_EQ(m.tangents.size(), 4u);
    expectOrthonormal(m);
    for (size_t t = 0; t < 2; ++t)
        for (size_t k = 0; k < 3; ++k) {
            expectNear(tangentAt(m, t, k), {1, 0, 0}, 1e-7);
            EXPECT_EQ(signAt(m, t, k), 1);  // N x T = +y = dp/dv
        }
    // The shared corners share their tangent.
    EXPECT_EQ(m.triangles[0].corners[0].tangent, m.triangles[1].corners[0].tangent);
    EXPECT_EQ(m.triangles[0].corners[2].tangent, m.triangles[1].corners[1].tangent);
}

TEST(Tangents, ATurnedLayoutTurnsTheTangent) {
    // u runs up the square (+y), v to the left (-x): dp/du = +y, and N x T = -x = dp/dv.
    MeshData m = square([](float x, float y) { return TexCoord{y, 1 - x}; });
    generateTangents(m);
    expectOrthonormal(m);
    for (size_t k = 0; k < 3; ++k) {
        expectNear(tangentAt(m, 0, k), {0, 1, 0}, 1e-7);
        EXPECT_EQ(signAt(m, 0, k), 1);
    }
}

TEST(Tangents, AMirroredLayoutHasSignMinusOne) {
    // u runs to the left: dp/du = -x; N x T = -y but dp/dv = +y: the frame is mirrored.
    MeshData m = square([](float x, float y) { return TexCoord{1 - x, y}; });
    TangentReport r = generateTangents(m);
    EXPECT_EQ(r.tangents, 4u);
    expectOrthonormal(m);
    for (size_t t = 0; t < 2; ++t)
        for (size_t k = 0; k < 3; ++k) {
            expectNear(tangentAt(m, t, k), {-1, 0, 0}, 1e-7);
            EXPECT_EQ(signAt(m, t, k), -1);
        }
}

TEST(Tangents, ASphereHasTangentsAlongDuOrthogonalToItsNormals) {
    // p(theta, phi) = (sin theta sin phi, cos theta, sin theta cos phi); u = phi / 2 pi,
    // v = 1 - theta / pi (v up: the north pole at the top of the image). dp/du points along
    // (cos phi, 0, -sin phi), and N x T points north, as dp/dv does: sign +1.
    const int rings = 24, segments = 48;
    MeshData m;
    auto vertex = [&](int i, int j) {
        const double theta = std::numbers::pi * i / rings,
                     phi = 2 * std::numbers::pi * j / segments;
        Vec3 p(std::sin(theta) * std::sin(phi), std::cos(theta), std::sin(theta) * std::cos(phi));
        m.positions.push_back(Vec3f(p));
        m.normals.push_back(Vec3f(p));
        m.uvs.push_back({float(j) / segments, 1 - float(i) / rings});
    };
    for (int i = 0; i <= rings; ++i)
        for (int j = 0; j <= segments; ++j) vertex(i, j);  // the seam's vertices twice (u 0, 1)
    auto id = [&](int i, int j) { return uint32_t(i * (segments + 1) + j); };
    for (int i = 0; i < rings; ++i)
        for (int j = 0; j < segments; ++j) {
            // Counter-clockwise seen from outside: (i, j) (i+1, j) (i+1, j+1) goes down, then
            // towards larger phi.
            if (i > 0) addTriangle(m, id(i, j), id(i + 1, j), id(i, j + 1));
            if (i < rings - 1) addTriangle(m, id(i, j + 1), id(i + 1, j), id(i + 1, j + 1));
        }
    // The winding is outward.
    const auto& t0 = m.triangles[0].corners;
    Vec3 a(m.positions[t0[0].position]), b(m.positions[t0[1].position]),
        c(m.positions[t0[2].position]);
    ASSERT_GT(dot(cross(b - a, c - a), a + b + c), 0);

    TangentReport r = generateTangents(m);
    EXPECT_EQ(r.triangles, m.triangles.size());
    EXPECT_EQ(r.fallback, 0u);
    expectOrthonormal(m, 1e-5);
    // An interior vertex's neighbours lie on both sides, and their errors cancel; at the seam a
    // vertex has triangles on one side only, whose chords turn by half a segment (3.75 degrees).
    const double seam = std::cos(std::numbers::pi / segments);
    size_t checked = 0;
    for (size_t t = 0; t < m.triangles.size(); ++t)
        for (size_t k = 0; k < 3; ++k) {
            const MeshData::Corner& corner = m.triangles[t].corners[k];
            Vec3 p(m.positions[corner.position]);
            const double theta = std::acos(std::clamp(p.y, -1.0, 1.0));
            if (std::sin(theta) < 0.2) continue;  // near the poles du has little meaning
            const double phi = 2 * std::numbers::pi * m.uvs[corner.uv][0];
            Vec3 du(std::cos(phi), 0, -std::sin(phi));
            EXPECT_GT(dot(tangentAt(m, t, k), du), seam - 1e-4)
                << "triangle " << t << " corner " << k;
            EXPECT_EQ(signAt(m, t, k), 1);
            ++checked;
        }
    EXPECT_GT(checked, m.triangles.size());
}

TEST(Tangents, AVertexWhereTheTextureIsMirroredIsSplitByHandedness) {
    // Triangle 0 maps the square as it is; triangle 1 shares the diagonal's corners with the
    // same uvs, but its third corner's uv lies on the same side of the diagonal: its layout is
    // mirrored (a uv fold).
    MeshData m = square([](float x, float y) { return TexCoord{x, y}; });
    m.uvs[3] = {1, 0};
    TangentReport r = generateTangents(m);
    EXPECT_EQ(r.tangents, 6u);  // corners 0 and 2 twice, 1 and 3 once
    expectOrthonormal(m);
    const auto& a = m.triangles[0].corners;
    const auto& b = m.triangles[1].corners;
    EXPECT_NE(a[0].tangent, b[0].tangent);  // vertex 0
    EXPECT_NE(a[2].tangent, b[1].tangent);  // vertex 2
    for (size_t k = 0; k < 3; ++k) {
        EXPECT_EQ(signAt(m, 0, k), 1);
        EXPECT_EQ(signAt(m, 1, k), -1);
    }
    // Triangle 1 maps (0,0), (1,1), (0,1) to (0,0), (1,1), (1,0): u = y and v = x, so dp/du
    // is +y (and dp/dv = +x, against N x T = -x).
    for (size_t k = 0; k < 3; ++k) expectNear(tangentAt(m, 1, k), {0, 1, 0}, 1e-7);
}

TEST(Tangents, TrianglesAroundAVertexAreWeightedByTheirAngles) {
    // Two triangles at the origin sharing the edge to (0, 1): A (a right angle, 90 degrees)
    // with uv = (x, y), dp/du = +x; B (45 degrees) with uv = (x, x + y), whose dp/du is
    // (1, -1) / sqrt 2. Both keep their orientation, and the shared corners weld.
    MeshData m;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {-1, 1, 0}};
    m.normals.assign(4, Vec3f(0, 0, 1));
    m.uvs = {{0, 0}, {1, 0}, {0, 1}, {-1, 0}};
    addTriangle(m, 0, 1, 2);
    addTriangle(m, 0, 2, 3);
    generateTangents(m);
    expectOrthonormal(m);
    const double a = std::numbers::pi / 2, b = std::numbers::pi / 4;
    Vec3 expected = normalize(Vec3(1, 0, 0) * a + normalize(Vec3(1, -1, 0)) * b);
    expectNear(tangentAt(m, 0, 0), expected, 1e-6);
    EXPECT_EQ(m.triangles[0].corners[0].tangent, m.triangles[1].corners[0].tangent);
    // At (0, 1), A's corner lies between (0, -1) and (1, -1): 45 degrees; B's between (-1, 0)
    // and (0, -1): 90 degrees.
    Vec3 top = normalize(Vec3(1, 0, 0) * (std::numbers::pi / 4) +
                         normalize(Vec3(1, -1, 0)) * (std::numbers::pi / 2));
    expectNear(tangentAt(m, 0, 2), top, 1e-6);
    // The corners no other triangle shares have their own triangle's tangent.
    expectNear(tangentAt(m, 0, 1), {1, 0, 0}, 1e-6);
    expectNear(tangentAt(m, 1, 2), normalize(Vec3(1, -1, 0)), 1e-6);
}

TEST(Tangents, DegenerateTextureCoordinatesGiveAFallbackNotNaN) {
    MeshData m = square([](float, float) { return TexCoord{0.5f, 0.5f}; });
    TangentReport r = generateTangents(m);
    EXPECT_EQ(r.triangles, 2u);
    EXPECT_GT(r.fallback, 0u);
    expectOrthonormal(m);
    // One degenerate triangle beside a good one: its shared corners take the good one's tangent.
    MeshData half = square([](float x, float y) { return TexCoord{x, y}; });
    half.uvs.push_back({0.5f, 0.5f});  // corner 3 of triangle 1 moves to a uv on the diagonal
    half.triangles[1].corners[2].uv = 4;
    r = generateTangents(half);
    EXPECT_EQ(r.fallback, 1u);  // triangle 1's own corner, whose vertex no good triangle shares
    expectOrthonormal(half);
    EXPECT_EQ(half.triangles[1].corners[0].tangent, half.triangles[0].corners[0].tangent);
    expectNear(tangentAt(half, 1, 1), {1, 0, 0}, 1e-7);
    EXPECT_EQ(signAt(half, 1, 2), 1);  // the neighbour's handedness
}

TEST(Tangents, TrianglesWithEqualCornersTakeTheTangentOfTheirVertex) {
    MeshData m = square([](float x, float y) { return TexCoord{x, y}; });
    addTriangle(m, 0, 0, 2);  // no area
    TangentReport r = generateTangents(m);
    EXPECT_EQ(r.triangles, 3u);
    expectOrthonormal(m);
    EXPECT_EQ(m.triangles[2].corners[0].tangent, m.triangles[0].corners[0].tangent);
    EXPECT_EQ(m.triangles[2].corners[2].tangent, m.triangles[0].corners[2].tangent);
}

TEST(Tangents, WithoutNormalsTheFaceNormalIsUsed) {
    MeshData m = square([](float x, float y) { return TexCoord{x, y}; });
    m.normals.clear();
    for (auto& t : m.triangles)
        for (auto& c : t.corners) c.normal = MeshData::kNone;
    m.positions[2].z = 0.5f;  // the two triangles are no longer coplanar
    generateTangents(m);
    for (size_t t = 0; t < 2; ++t) {
        const auto& c = m.triangles[t].corners;
        Vec3 p0(m.positions[c[0].position]), p1(m.positions[c[1].position]),
            p2(m.positions[c[2].position]);
        Vec3 face = normalize(cross(p1 - p0, p2 - p0));
        for (size_t k = 0; k < 3; ++k) {
            EXPECT_NEAR(dot(tangentAt(m, t, k), face), 0, 1e-6);
            EXPECT_EQ(signAt(m, t, k), 1);
        }
    }
    // The corners of the two faces differ in normal: they do not weld.
    EXPECT_EQ(m.tangents.size(), 6u);
}

TEST(Tangents, TheRequestChoosesTrianglesAndTextureCoordinates) {
    MeshData m = square([](float x, float y) { return TexCoord{x, y}; });
    for (const Vec3f& p : m.positions) m.uv1s.push_back({p.y, 1 - p.x});  // dp/du1 = +y
    for (auto& t : m.triangles)
        for (size_t k = 0; k < 3; ++k) t.corners[k].uv1 = t.corners[k].position;
    m.triangles[1].material = 7;
    TangentRequest request;
    request.secondUvs = true;
    request.select = [](const MeshData::Triangle& t) { return t.material == 7; };
    TangentReport r = generateTangents(m, request);
    EXPECT_EQ(r.triangles, 1u);
    EXPECT_EQ(m.triangles[0].corners[0].tangent, MeshData::kNone);
    for (size_t k = 0; k < 3; ++k) expectNear(tangentAt(m, 1, k), {0, 1, 0}, 1e-7);
    // A range that excludes it does nothing; triangles that have tangents keep them.
    const size_t before = m.tangents.size();
    request.select = nullptr;
    request.first = 1;
    r = generateTangents(m, request);
    EXPECT_EQ(r.triangles, 0u);
    EXPECT_EQ(m.tangents.size(), before);
    // Without the coordinates asked for, nothing is generated.
    MeshData bare = square([](float x, float y) { return TexCoord{x, y}; });
    TangentRequest second;
    second.secondUvs = true;
    EXPECT_EQ(generateTangents(bare, second).triangles, 0u);
    EXPECT_TRUE(bare.tangents.empty());
}

}  // namespace
}  // namespace glint
