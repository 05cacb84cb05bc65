// The web build's SIMD128 traversal kernels against the portable ones, bit for bit (the web
// twin of the native Bvh.KernelSetsGiveIdenticalHits, which runs AVX2 against portable). Built
// by `make web` into the single-threaded build folder (web/CMakeLists.txt) and run by CTest in
// Node as web.simd128_kernels:
//
//   node --no-experimental-fetch build-web/st/glint-kernels-test.js
//
// Random triangles of every size (leaves of triangle blocks, the SIMD part), triangles sharing
// edges and lying in axis planes (hits on edges and vertices, ties), spheres and other shapes
// (the scalar leaf code, the same in both), planes; single rays (closest hit, any hit) and
// packets of eight (coherent, with spread origins, with inactive lanes, incoherent). Every
// answer must be identical: hit or miss, t to the bit, primitive id. Exit status 1 otherwise.

#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>

#include "glint/accel/bvh.h"
#include "glint/math/mat4.h"
#include "glint/math/rng.h"
#include "unit/random_geometry.h"

namespace glint {
namespace {

using test::Random;

void addScene(Primitives& prims, Random& r) {
    // Triangles of sizes 0.01 to 10 within about [-12, 12]^3.
    for (int i = 0; i < 6000; ++i) {
        Vec3 c = r.point(-10, 10);
        double size = std::pow(10.0, r.uni(-2, 1));
        prims.addTriangle(c + r.direction() * size, c + r.direction() * size,
                          c + r.direction() * size, nullptr, 0);
    }
    // A grid of axis-aligned squares split into triangle pairs, on integer coordinates: rays
    // meet shared edges and vertices exactly, and some squares repeat (ties broken by id).
    for (int x = -4; x < 4; ++x)
        for (int y = -4; y < 4; ++y) {
            Vec3 a(x, y, 2), b(x + 1, y, 2), c(x + 1, y + 1, 2), d(x, y + 1, 2);
            prims.addTriangle(a, b, c, nullptr, 0);
            prims.addTriangle(a, c, d, nullptr, 0);
            if ((x + y) % 3 == 0) prims.addTriangle(a, b, c, nullptr, 0);
        }
    for (int i = 0; i < 300; ++i) {
        Vec3 c = r.point(-10, 10);
        Mat4 m = Mat4::translate(c.x, c.y, c.z) *
                 Mat4::scale(r.uni(0.2, 2), r.uni(0.2, 2), r.uni(0.2, 2));
        prims.addSphere(Sphere{r.point(-0.2, 0.2), r.uni(0.05, 1.5), *Transform::fromMatrix(m)}, 0);
    }
    for (int i = 0; i < 200; ++i) {
        double size = r.uni(0.1, 2);
        Vec3 c = r.point(-10, 10), a = c + r.point(-size, size), b = c + r.point(-size, size);
        prims.addShape(Shape{ShapeKind::Box, 1, *Transform::fromMatrix(boxPlacement(a, b))}, 0);
    }
    auto plane = Plane::make(Vec3(0, -13, 0), Vec3(0, 1, 0), Transform{});
    if (plane) prims.addPlane(*plane, 0);
}

/// Half aimed at a primitive, some along the axes or at the grid's integer points, a third
/// with a finite tMax, some with tMin > 0.
Ray randomRay(const Primitives& prims, Random& r, int i) {
    Vec3 origin = r.point(-15, 15);
    Vec3 dir = r.direction();
    if (i % 2 == 0) {
        Vec3 target(prims.bounds(r.below(prims.boundedCount())).centroid());
        if (length(target - origin) > 1e-3) dir = normalize(target - origin + r.point(-0.1, 0.1));
    }
    if (i % 11 == 0) {
        dir = {};
        dir[static_cast<int>(r.below(3))] = r.uni(0, 1) < 0.5 ? -1 : 1;
    }
    if (i % 13 == 0) {  // through a grid vertex or edge point
        Vec3 target(static_cast<double>(r.below(8)) - 4, static_cast<double>(r.below(16)) / 2 - 4,
                    2);
        origin = Vec3(r.uni(-3, 3), r.uni(-3, 3), r.uni(5, 10));
        dir = normalize(target - origin);
    }
    Ray ray{origin, dir, 0, kInfinity};
    if (i % 3 == 0) ray.tMax = r.uni(0.1, 30);
    if (i % 7 == 0) ray.tMin = r.uni(0, 5);
    return ray;
}

RayPacket8 randomPacket(const Primitives& prims, Random& r, int p) {
    RayPacket8 packet;
    packet.active = static_cast<uint8_t>(p % 5 == 0 ? r.below(256) : 0xff);
    Vec3 origin = r.point(-15, 15), base = r.direction();
    if (p % 2 == 0)
        base = normalize(Vec3(prims.bounds(r.below(prims.boundedCount())).centroid()) - origin +
                         r.point(-1, 1));
    for (int i = 0; i < 8; ++i) {
        Ray ray;
        switch (p % 3) {
            case 0:
                ray = Ray{origin, normalize(base + r.point(-0.05, 0.05)), 0, kInfinity};
                break;
            case 1:
                ray = Ray{origin + r.point(-0.1, 0.1), normalize(base + r.point(-0.05, 0.05)), 0,
                          r.uni(0, 1) < 0.5 ? kInfinity : r.uni(1, 30)};
                break;
            default:
                ray = randomRay(prims, r, i);
        }
        packet.set(i, TraversalRay(ray));
    }
    return packet;
}

bool same(const Hit& a, const Hit& b) {
    return std::memcmp(&a.t, &b.t, sizeof(float)) == 0 && a.primId == b.primId;
}

}  // namespace
}  // namespace glint

int main() {
    using namespace glint;
    if (Bvh::bestIsa() != Isa::Simd128) {
        std::printf("FAIL: the default kernels are %s, not simd128\n", Bvh::isa());
        return 1;
    }
    Primitives prims;
    Random r(5);
    addScene(prims, r);
    Bvh portable, simd;
    portable.build(prims, {1, Isa::Portable});
    simd.build(prims, {1, Isa::Simd128});
    if (simd.kernels() != Isa::Simd128 || portable.kernels() != Isa::Portable) {
        std::printf("FAIL: the BVHs do not use the kernels asked for\n");
        return 1;
    }
    int rays = 0, hits = 0, triangleHits = 0, occluded = 0, differ = 0;
    std::string first;
    auto report = [&](const std::string& what) {
        if (differ++ == 0) first = what;
    };
    for (int i = 0; i < 100000; ++i) {
        TraversalRay ray(randomRay(prims, r, i));
        Hit a, b;
        bool fa = portable.intersect(ray, a), fb = simd.intersect(ray, b);
        ++rays;
        hits += fa;
        triangleHits += fa && a.primId < prims.triangleCount();
        if (fa != fb || !same(a, b))
            report("ray " + std::to_string(i) + ": portable t " + std::to_string(a.t) + " id " +
                   std::to_string(a.primId) + ", simd128 t " + std::to_string(b.t) + " id " +
                   std::to_string(b.primId));
        bool oa = portable.occluded(ray), ob = simd.occluded(ray);
        occluded += oa;
        if (oa != ob) report("ray " + std::to_string(i) + ": occluded differs");
    }
    int lanes = 0, laneHits = 0;
    for (int p = 0; p < 20000; ++p) {
        RayPacket8 packet = randomPacket(prims, r, p);
        HitPacket8 a, b;
        portable.intersect8(packet, a);
        simd.intersect8(packet, b);
        for (int i = 0; i < 8; ++i) {
            if (!(packet.active >> i & 1)) continue;
            ++lanes;
            laneHits += a.t[i] < kInfinity;
            if (!same(a[i], b[i]))
                report("packet " + std::to_string(p) + " lane " + std::to_string(i) +
                       ": portable t " + std::to_string(a.t[i]) + ", simd128 t " +
                       std::to_string(b.t[i]));
        }
    }
    std::printf(
        "%d rays (%d hits, %d on triangles; %d occluded), %d packet lanes (%d hits): %d "
        "differences\n",
        rays, hits, triangleHits, occluded, lanes, laneHits, differ);
    // The rays must exercise both answers, and the triangle tests, or agreeing would prove
    // little.
    if (hits < rays / 4 || hits == rays || triangleHits < rays / 10 || laneHits < lanes / 4 ||
        laneHits == lanes) {
        std::printf("FAIL: too few or too many hits to compare\n");
        return 1;
    }
    if (differ) std::printf("FAIL: first difference: %s\n", first.c_str());
    return differ ? 1 : 0;
}
