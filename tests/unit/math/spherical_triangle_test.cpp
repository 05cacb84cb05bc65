// Spherical triangles (math/spherical_triangle.h): the solid angle against known ones and
// against counting random directions, and sampled directions that all meet the triangle,
// spread uniformly over its solid angle (each of its four midpoint sub-triangles gets its
// share, by chi-square).

#include "glint/math/spherical_triangle.h"

#include <gtest/gtest.h>

#include <numbers>

#include "glint/math/rng.h"

namespace glint {
namespace {

constexpr double kPi = std::numbers::pi;

/// Whether the ray from `p` along `d` meets triangle (A, B, C), and where (barycentrics of B
/// and C, in `bc`).
bool meets(const Vec3& p, const Vec3& d, const Vec3& A, const Vec3& B, const Vec3& C,
           double bc[2]) {
    const Vec3 e1 = B - A, e2 = C - A, s = cross(d, e2);
    const double det = dot(e1, s);
    if (std::abs(det) < 1e-14) return false;
    const Vec3 t = p - A;
    const double b1 = dot(t, s) / det;
    const Vec3 q = cross(t, e1);
    const double b2 = dot(d, q) / det;
    const double dist = dot(e2, q) / det;
    bc[0] = b1;
    bc[1] = b2;
    const double slack = -1e-9;
    return dist > 0 && b1 >= slack && b2 >= slack && b1 + b2 <= 1 - slack;
}

Vec3 dirTo(const Vec3& p, const Vec3& x) { return normalize(x - p); }

TEST(SphericalTriangle, AreaOfAnOctantIsPiOverTwo) {
    EXPECT_NEAR(sphericalTriangleArea({1, 0, 0}, {0, 1, 0}, {0, 0, 1}), kPi / 2, 1e-12);
    // Order and orientation do not matter.
    EXPECT_NEAR(sphericalTriangleArea({0, 0, 1}, {0, 1, 0}, {1, 0, 0}), kPi / 2, 1e-12);
}

TEST(SphericalTriangle, SamplesMeetTheTriangleUniformlyOverItsSolidAngle) {
    struct Case {
        Vec3 p, A, B, C;
    } cases[] = {
        {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}},                     // an octant
        {{0.2, 0.3, -1}, {-1, -1, 0}, {2, -0.5, 0.3}, {0.1, 1.5, -0.2}},  // near and large
        {{0, 5, 0}, {-0.3, 0, -0.2}, {0.4, 0.1, 0}, {0, 0, 0.5}},         // far and small
        {{0, 0.05, 0}, {-3, 0, -3}, {3, 0, -3}, {0, 0, 3}},               // nearly a hemisphere
        {{2, 0.01, 0}, {0, 0, 0}, {1, 0, 0}, {0, 0, 1}},                  // seen edge-on
    };
    Rng rng(9);
    for (const Case& k : cases) {
        const Vec3 a = dirTo(k.p, k.A), b = dirTo(k.p, k.B), c = dirTo(k.p, k.C);
        const double area = sphericalTriangleArea(a, b, c);
        // Four sub-triangles at the edges' midpoints, and their solid angles.
        const Vec3 mAB = (k.A + k.B) * 0.5, mBC = (k.B + k.C) * 0.5, mCA = (k.C + k.A) * 0.5;
        const Vec3 sub[4][3] = {{k.A, mAB, mCA}, {mAB, k.B, mBC}, {mCA, mBC, k.C}, {mAB, mBC, mCA}};
        double expected[4], total = 0;
        for (int s = 0; s < 4; ++s) {
            expected[s] = sphericalTriangleArea(dirTo(k.p, sub[s][0]), dirTo(k.p, sub[s][1]),
                                                dirTo(k.p, sub[s][2])) /
                          area;
            total += expected[s];
        }
        ASSERT_NEAR(total, 1, 1e-9);
        const int n = 40000;
        int counts[4] = {0, 0, 0, 0}, missed = 0;
        for (int i = 0; i < n; ++i) {
            const std::optional<Vec3> d =
                sampleSphericalTriangle(a, b, c, {rng.uniform(), rng.uniform()});
            ASSERT_TRUE(d);
            EXPECT_NEAR(length(*d), 1, 1e-9);
            double bc[2];
            if (!meets(k.p, *d, k.A, k.B, k.C, bc)) {
                ++missed;
                continue;
            }
            // Which sub-triangle: by the barycentrics of B (bc[0]) and C (bc[1]).
            const double wa = 1 - bc[0] - bc[1];
            const int s = wa >= 0.5 ? 0 : bc[0] >= 0.5 ? 1 : bc[1] >= 0.5 ? 2 : 3;
            counts[s]++;
        }
        EXPECT_LE(missed, n / 10000) << "directions that miss the triangle";
        double chi2 = 0;
        for (int s = 0; s < 4; ++s) {
            const double e = expected[s] * (n - missed);
            chi2 += (counts[s] - e) * (counts[s] - e) / e;
        }
        EXPECT_LT(chi2, 16.3) << "3 degrees of freedom, 99.9%: triangle seen from " << k.p.x << ","
                              << k.p.y << "," << k.p.z;
    }
}

TEST(SphericalTriangle, DegenerateTrianglesGiveNone) {
    EXPECT_FALSE(sampleSphericalTriangle({1, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.3, 0.6}));
}

}  // namespace
}  // namespace glint
