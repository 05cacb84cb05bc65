#pragma once
// The benchmark mesh of issue 3: a rippled torus of 2 * NU * NV flat triangles over a ground
// plane y = 0, with its camera and light. Shared by the scene generator and the traversal
// benchmark so that Glint, Embree and POV-Ray see exactly the same triangles.

#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

namespace glint::bench {

struct Mesh {
    std::vector<std::array<double, 3>> vertices;
    /// As issue 3 defines them: (a, b, c), (a, c, d) per quad. That winding faces into the tube,
    /// which traversal does not care about; renderable files reverse it (gen_scenes.cpp).
    std::vector<std::array<uint32_t, 3>> triangles;
};

/// NU x NV quads, two triangles each: the torus of issue 3 (R = 1, r = 0.35, ripple amplitude
/// 0.1 with 24 x 12 ripples), resting just above y = 0.
inline Mesh rippledTorus(int nu = 1000, int nv = 500) {
    constexpr double R = 1, r = 0.35, A = 0.1, KU = 24, KV = 12;
    Mesh m;
    m.vertices.reserve(static_cast<size_t>(nu) * nv);
    for (int i = 0; i < nu; ++i)
        for (int j = 0; j < nv; ++j) {
            double u = 2 * std::numbers::pi * i / nu, v = 2 * std::numbers::pi * j / nv;
            double rr = r * (1 + A * std::sin(KU * u) * std::sin(KV * v));
            m.vertices.push_back({(R + rr * std::cos(v)) * std::cos(u),
                                  r * (1 + A) + 0.001 + rr * std::sin(v),
                                  (R + rr * std::cos(v)) * std::sin(u)});
        }
    m.triangles.reserve(2 * static_cast<size_t>(nu) * nv);
    auto id = [nv](int i, int j) { return static_cast<uint32_t>(i * nv + j); };
    for (int i = 0; i < nu; ++i)
        for (int j = 0; j < nv; ++j) {
            uint32_t a = id(i, j), b = id((i + 1) % nu, j), c = id((i + 1) % nu, (j + 1) % nv),
                     d = id(i, (j + 1) % nv);
            m.triangles.push_back({a, b, c});
            m.triangles.push_back({a, c, d});
        }
    return m;
}

/// Appends the ground plane y = 0 as a square of two triangles facing +y.
inline void addGround(Mesh& m, double halfSize = 100) {
    auto base = static_cast<uint32_t>(m.vertices.size());
    m.vertices.push_back({-halfSize, 0, -halfSize});
    m.vertices.push_back({halfSize, 0, -halfSize});
    m.vertices.push_back({halfSize, 0, halfSize});
    m.vertices.push_back({-halfSize, 0, halfSize});
    m.triangles.push_back({base, base + 2, base + 1});
    m.triangles.push_back({base, base + 3, base + 2});
}

/// The view of issue 3: from (0, 2.2, -3.4) at (0, 0.2, 0), 60 degrees horizontal field of view,
/// 1280 x 720; one point light at (3, 5, -3).
struct View {
    std::array<double, 3> eye{0, 2.2, -3.4}, at{0, 0.2, 0}, up{0, 1, 0};
    double fovxDegrees = 60;
    int width = 1280, height = 720;
    std::array<double, 3> light{3, 5, -3};

    /// The vertical field of view the CSE167x `camera` command takes.
    double fovyDegrees() const {
        double tanX = std::tan(fovxDegrees * std::numbers::pi / 360);
        return 2 * std::atan(tanX * height / width) * 180 / std::numbers::pi;
    }
};

}  // namespace glint::bench
