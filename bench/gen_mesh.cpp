// glint_gen_mesh [OPTIONS] OUT.obj: writes a finely subdivided smooth surface as a Wavefront OBJ
// with vertex normals, for benchmarking the OBJ loader and `glint model.obj` on a real-sized
// mesh (docs/performance.md, "Meshes"). Nothing is downloaded: the surface is computed.
//
// The surface is a rippled tube around a trefoil knot, the (2, 3) torus knot
//   C(t) = ((2 + cos 3t) cos 2t, (2 + cos 3t) sin 2t, -sin 3t),
// of radius 0.45 (1 + 0.08 sin(40 t) cos(6 s)) around the curve, in its Frenet frame. The grid
// has SEGMENTS steps along the knot and SIDES around the tube, two triangles per cell, so
// 2 x SEGMENTS x SIDES triangles (default 2048 x 256: 1,048,576) and SEGMENTS x SIDES vertices,
// each with its exact unit normal (from the surface's partial derivatives) and, with --uv,
// texture coordinates (u along the knot, v around it; the seams repeat their vertices).
//
//   --segments N   steps along the knot (default 2048)
//   --sides N      steps around the tube (default 256)
//   --uv           write texture coordinates too

#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <string>
#include <string_view>
#include <vector>

namespace {

using V = std::array<double, 3>;

V operator+(V a, V b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
V operator-(V a, V b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
V operator*(V a, double s) { return {a[0] * s, a[1] * s, a[2] * s}; }
V cross(V a, V b) {
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double dot(V a, V b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
V normalize(V a) { return a * (1 / std::sqrt(dot(a, a))); }

constexpr double kTwoPi = 2 * std::numbers::pi;

/// The knot and its first two derivatives at t.
V knot(double t) {
    double r = 2 + std::cos(3 * t);
    return {r * std::cos(2 * t), r * std::sin(2 * t), -std::sin(3 * t)};
}
V knotD1(double t) {
    double r = 2 + std::cos(3 * t), dr = -3 * std::sin(3 * t);
    return {dr * std::cos(2 * t) - 2 * r * std::sin(2 * t),
            dr * std::sin(2 * t) + 2 * r * std::cos(2 * t), -3 * std::cos(3 * t)};
}
V knotD2(double t) {
    double r = 2 + std::cos(3 * t), dr = -3 * std::sin(3 * t), ddr = -9 * std::cos(3 * t);
    return {ddr * std::cos(2 * t) - 4 * dr * std::sin(2 * t) - 4 * r * std::cos(2 * t),
            ddr * std::sin(2 * t) + 4 * dr * std::cos(2 * t) - 4 * r * std::sin(2 * t),
            9 * std::sin(3 * t)};
}

/// The surface point at (t along the knot, s around the tube), both in [0, 2 pi).
V surface(double t, double s) {
    V d1 = knotD1(t), d2 = knotD2(t);
    V tangent = normalize(d1);
    V binormal = normalize(cross(d1, d2));
    V normal = cross(binormal, tangent);
    double radius = 0.45 * (1 + 0.08 * std::sin(40 * t) * std::cos(6 * s));
    return knot(t) + (normal * std::cos(s) + binormal * std::sin(s)) * radius;
}

/// Outward unit normal from the partial derivatives (central differences of the exact map).
V surfaceNormal(double t, double s) {
    const double h = 1e-5;
    V dt = surface(t + h, s) - surface(t - h, s);
    V ds = surface(t, s + h) - surface(t, s - h);
    return normalize(cross(ds, dt));
}

/// Text output through std::to_chars into one buffer.
struct Out {
    std::string text;
    void put(std::string_view s) { text.append(s); }
    void put(double v) {
        char buf[32];
        auto r = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::general, 7);
        text.append(buf, r.ptr);
    }
    void put(long long v) {
        char buf[24];
        auto r = std::to_chars(buf, buf + sizeof buf, v);
        text.append(buf, r.ptr);
    }
};

int usage() {
    std::fprintf(stderr, "usage: glint_gen_mesh [--segments N] [--sides N] [--uv] OUT.obj\n");
    return 2;
}

}  // namespace

int main(int argc, char** argv) {
    long long segments = 2048, sides = 256;
    bool uv = false;
    std::string path;
    for (int i = 1; i < argc; ++i) {
        std::string_view a = argv[i];
        if ((a == "--segments" || a == "--sides") && i + 1 < argc) {
            long long v = std::atoll(argv[++i]);
            if (v < 3 || v > 100000) return usage();
            (a == "--segments" ? segments : sides) = v;
        } else if (a == "--uv") {
            uv = true;
        } else if (!a.empty() && a[0] != '-' && path.empty()) {
            path = a;
        } else {
            return usage();
        }
    }
    if (path.empty()) return usage();

    // With texture coordinates the seams need their own vertices (u = 1, v = 1).
    const long long columns = segments + (uv ? 1 : 0), rows = sides + (uv ? 1 : 0);
    Out out;
    out.text.reserve(static_cast<size_t>(columns * rows * (uv ? 90 : 70) + segments * sides * 50));
    out.put("# Trefoil knot tube, ");
    out.put(2 * segments * sides);
    out.put(" triangles, written by glint_gen_mesh (bench/gen_mesh.cpp)\n");
    for (long long i = 0; i < columns; ++i)
        for (long long j = 0; j < rows; ++j) {
            double t = kTwoPi * static_cast<double>(i) / static_cast<double>(segments);
            double s = kTwoPi * static_cast<double>(j) / static_cast<double>(sides);
            V p = surface(t, s), n = surfaceNormal(t, s);
            out.put("v ");
            out.put(p[0]), out.put(" "), out.put(p[1]), out.put(" "), out.put(p[2]);
            out.put("\nvn ");
            out.put(n[0]), out.put(" "), out.put(n[1]), out.put(" "), out.put(n[2]);
            out.put("\n");
            if (uv) {
                out.put("vt ");
                out.put(static_cast<double>(i) / static_cast<double>(segments));
                out.put(" ");
                out.put(static_cast<double>(j) / static_cast<double>(sides));
                out.put("\n");
            }
        }
    // Vertex (i, j) is number i * rows + j + 1; cells wrap around both ways without --uv.
    auto index = [&](long long i, long long j) {
        if (!uv) i %= segments, j %= sides;
        return i * rows + j + 1;
    };
    auto corner = [&](long long k) {
        out.put(k);
        out.put(uv ? "/" : "//");
        if (uv) {
            out.put(k);
            out.put("/");
        }
        out.put(k);
    };
    for (long long i = 0; i < segments; ++i)
        for (long long j = 0; j < sides; ++j) {
            long long a = index(i, j), b = index(i + 1, j), c = index(i + 1, j + 1),
                      d = index(i, j + 1);
            // Counter-clockwise seen from outside: around the tube, s turns left-handed about
            // the knot's tangent, so the outward normal is ds x dt and the cell (a, b, c, d)
            // runs clockwise seen from outside; its triangles are written the other way round.
            out.put("f "), corner(a), out.put(" "), corner(c), out.put(" "), corner(b);
            out.put("\nf "), corner(a), out.put(" "), corner(d), out.put(" "), corner(c);
            out.put("\n");
        }
    FILE* f = std::fopen(path.c_str(), "wb");
    if (!f || std::fwrite(out.text.data(), 1, out.text.size(), f) != out.text.size() ||
        std::fclose(f) != 0) {
        std::perror(path.c_str());
        return 1;
    }
    std::printf("%s: %lld vertices, %lld triangles, %.1f MB\n", path.c_str(), columns * rows,
                2 * segments * sides, static_cast<double>(out.text.size()) / 1e6);
    return 0;
}
