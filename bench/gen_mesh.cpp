// glint_gen_mesh [OPTIONS] OUT.obj|OUT.glb|OUT.ply|OUT.stl: writes a finely subdivided smooth
// surface as a Wavefront OBJ, a binary glTF, a PLY (binary little-endian unless --ascii or
// --big-endian) or an STL (binary unless --ascii), by the name's extension, with vertex normals
// (but STL, which has none), for benchmarking the mesh loaders and `glint model.obj` on a
// real-sized mesh (docs/performance.md, "Meshes"). Nothing is downloaded: the surface is
// computed. Every format holds the same vertices and triangles (the binary ones in float, 32-bit
// indices, no material; STL repeats each triangle's three corners).
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
//   --uv           write texture coordinates too (OBJ, glTF, PLY)
//   --ascii        PLY and STL: the text form
//   --big-endian   PLY: binary big-endian

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
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

/// The surface: vertices with normals (and texture coordinates), triangles of vertex numbers
/// counted from 0, counter-clockwise seen from outside.
struct Mesh {
    std::vector<V> p, n;
    std::vector<std::array<double, 2>> uv;  ///< Empty without --uv.
    std::vector<std::array<long long, 3>> tri;
};

/// The mesh as OBJ text (indices from 1).
std::string objText(const Mesh& mesh) {
    const bool uv = !mesh.uv.empty();
    Out out;
    out.text.reserve(mesh.p.size() * (uv ? 90 : 70) + mesh.tri.size() * 25);
    out.put("# Trefoil knot tube, ");
    out.put(static_cast<long long>(mesh.tri.size()));
    out.put(" triangles, written by glint_gen_mesh (bench/gen_mesh.cpp)\n");
    for (size_t k = 0; k < mesh.p.size(); ++k) {
        const V &p = mesh.p[k], &n = mesh.n[k];
        out.put("v ");
        out.put(p[0]), out.put(" "), out.put(p[1]), out.put(" "), out.put(p[2]);
        out.put("\nvn ");
        out.put(n[0]), out.put(" "), out.put(n[1]), out.put(" "), out.put(n[2]);
        out.put("\n");
        if (uv) {
            out.put("vt ");
            out.put(mesh.uv[k][0]);
            out.put(" ");
            out.put(mesh.uv[k][1]);
            out.put("\n");
        }
    }
    auto corner = [&](long long k) {
        out.put(k + 1);
        out.put(uv ? "/" : "//");
        if (uv) {
            out.put(k + 1);
            out.put("/");
        }
        out.put(k + 1);
    };
    for (const auto& t : mesh.tri) {
        out.put("f "), corner(t[0]), out.put(" "), corner(t[1]), out.put(" "), corner(t[2]);
        out.put("\n");
    }
    return std::move(out.text);
}

/// The mesh as a binary glTF: one buffer of float positions, normals (and texture
/// coordinates, v turned down as glTF has it) and 32-bit indices; one node, no material.
std::string glbFile(const Mesh& mesh) {
    std::string bin;
    auto floats = [&](const auto& values) {
        for (double x : values) {
            float f = static_cast<float>(x);
            bin.append(reinterpret_cast<const char*>(&f), 4);
        }
    };
    std::string views, accessors, attributes;
    int view = 0;
    auto add = [&](size_t start, const char* type, int componentType, size_t count,
                   const std::string& extra) {
        views += std::string(view ? "," : "") +
                 "{\"buffer\":0,\"byteOffset\":" + std::to_string(start) +
                 ",\"byteLength\":" + std::to_string(bin.size() - start) + "}";
        accessors += std::string(view ? "," : "") + "{\"bufferView\":" + std::to_string(view) +
                     ",\"componentType\":" + std::to_string(componentType) +
                     ",\"count\":" + std::to_string(count) + ",\"type\":\"" + type + "\"" + extra +
                     "}";
        return view++;
    };
    V lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
    size_t start = bin.size();
    for (const V& p : mesh.p) {
        floats(p);
        for (int i = 0; i < 3; ++i) {
            lo[i] = std::min(lo[i], static_cast<double>(static_cast<float>(p[i])));
            hi[i] = std::max(hi[i], static_cast<double>(static_cast<float>(p[i])));
        }
    }
    auto list = [](const V& v) {
        char buf[96];
        std::snprintf(buf, sizeof buf, "[%.9g,%.9g,%.9g]", v[0], v[1], v[2]);
        return std::string(buf);
    };
    attributes +=
        "\"POSITION\":" + std::to_string(add(start, "VEC3", 5126, mesh.p.size(),
                                             ",\"min\":" + list(lo) + ",\"max\":" + list(hi)));
    start = bin.size();
    for (const V& n : mesh.n) floats(n);
    attributes += ",\"NORMAL\":" + std::to_string(add(start, "VEC3", 5126, mesh.n.size(), ""));
    if (!mesh.uv.empty()) {
        start = bin.size();
        for (const auto& t : mesh.uv) floats(std::array<double, 2>{t[0], 1 - t[1]});
        attributes +=
            ",\"TEXCOORD_0\":" + std::to_string(add(start, "VEC2", 5126, mesh.uv.size(), ""));
    }
    start = bin.size();
    for (const auto& t : mesh.tri)
        for (long long k : t) {
            uint32_t i = static_cast<uint32_t>(k);
            bin.append(reinterpret_cast<const char*>(&i), 4);
        }
    int indices = add(start, "SCALAR", 5125, 3 * mesh.tri.size(), "");
    std::string json =
        "{\"asset\":{\"version\":\"2.0\",\"generator\":\"glint_gen_mesh "
        "(bench/gen_mesh.cpp)\"},\"scene\":0,\"scenes\":[{\"nodes\":[0]}],"
        "\"nodes\":[{\"mesh\":0}],\"meshes\":[{\"name\":\"trefoil\","
        "\"primitives\":[{\"attributes\":{" +
        attributes + "},\"indices\":" + std::to_string(indices) +
        "}]}],\"buffers\":[{\"byteLength\":" + std::to_string(bin.size()) + "}],\"bufferViews\":[" +
        views + "],\"accessors\":[" + accessors + "]}";
    json.append((4 - json.size() % 4) % 4, ' ');
    auto u32 = [](size_t x) {
        uint32_t v = static_cast<uint32_t>(x);
        return std::string(reinterpret_cast<const char*>(&v), 4);
    };
    return "glTF" + u32(2) + u32(12 + 8 + json.size() + 8 + bin.size()) + u32(json.size()) +
           "JSON" + json + u32(bin.size()) + std::string("BIN\0", 4) + bin;
}

/// The mesh as PLY: x y z nx ny nz (s t) per vertex, faces as `list uchar int vertex_indices`.
std::string plyFile(const Mesh& mesh, bool ascii, bool bigEndian) {
    const bool uv = !mesh.uv.empty();
    Out out;
    out.put("ply\nformat ");
    out.put(ascii ? "ascii" : bigEndian ? "binary_big_endian" : "binary_little_endian");
    out.put(" 1.0\ncomment written by glint_gen_mesh (bench/gen_mesh.cpp)\nelement vertex ");
    out.put(static_cast<long long>(mesh.p.size()));
    out.put(
        "\nproperty float x\nproperty float y\nproperty float z\nproperty float nx\n"
        "property float ny\nproperty float nz\n");
    if (uv) out.put("property float s\nproperty float t\n");
    out.put("element face ");
    out.put(static_cast<long long>(mesh.tri.size()));
    out.put("\nproperty list uchar int vertex_indices\nend_header\n");
    auto bytes = [&](const void* p, size_t n) {
        const char* c = static_cast<const char*>(p);
        for (size_t i = 0; i < n; ++i) out.text.push_back(c[bigEndian ? n - 1 - i : i]);
    };
    auto value = [&](double v, bool last) {
        if (ascii) {
            out.put(static_cast<double>(static_cast<float>(v)));
            out.put(last ? "\n" : " ");
        } else {
            float f = static_cast<float>(v);
            bytes(&f, 4);
        }
    };
    out.text.reserve(out.text.size() + mesh.p.size() * (ascii ? 80 : 32) + mesh.tri.size() * 24);
    for (size_t k = 0; k < mesh.p.size(); ++k) {
        for (double c : mesh.p[k]) value(c, false);
        for (int i = 0; i < 3; ++i) value(mesh.n[k][i], i == 2 && !uv);
        if (uv) value(mesh.uv[k][0], false), value(mesh.uv[k][1], true);
    }
    for (const auto& t : mesh.tri) {
        if (ascii) {
            out.put("3 "), out.put(t[0]), out.put(" "), out.put(t[1]), out.put(" "), out.put(t[2]);
            out.put("\n");
        } else {
            out.text.push_back(3);
            for (long long k : t) {
                int32_t i = static_cast<int32_t>(k);
                bytes(&i, 4);
            }
        }
    }
    return std::move(out.text);
}

/// The mesh as STL: each triangle's corners (and its unit normal) in float.
std::string stlFile(const Mesh& mesh, bool ascii) {
    Out out;
    auto facetNormal = [&](const std::array<long long, 3>& t) {
        V n = cross(mesh.p[t[1]] - mesh.p[t[0]], mesh.p[t[2]] - mesh.p[t[0]]);
        double len = std::sqrt(dot(n, n));
        return len > 0 ? n * (1 / len) : V{0, 0, 0};
    };
    if (ascii) {
        out.text.reserve(mesh.tri.size() * 260);
        out.put("solid trefoil\n");
        for (const auto& t : mesh.tri) {
            V n = facetNormal(t);
            out.put("  facet normal ");
            out.put(n[0]), out.put(" "), out.put(n[1]), out.put(" "), out.put(n[2]);
            out.put("\n    outer loop\n");
            for (long long k : t) {
                out.put("      vertex ");
                const V& p = mesh.p[k];
                out.put(static_cast<double>(static_cast<float>(p[0]))), out.put(" ");
                out.put(static_cast<double>(static_cast<float>(p[1]))), out.put(" ");
                out.put(static_cast<double>(static_cast<float>(p[2]))), out.put("\n");
            }
            out.put("    endloop\n  endfacet\n");
        }
        out.put("endsolid trefoil\n");
        return std::move(out.text);
    }
    std::string bin = "binary STL written by glint_gen_mesh (bench/gen_mesh.cpp)";
    bin.resize(80, ' ');
    bin.reserve(84 + 50 * mesh.tri.size());
    auto u32 = [&](uint32_t v) { bin.append(reinterpret_cast<const char*>(&v), 4); };
    auto f32 = [&](double v) {
        float f = static_cast<float>(v);
        bin.append(reinterpret_cast<const char*>(&f), 4);
    };
    u32(static_cast<uint32_t>(mesh.tri.size()));
    for (const auto& t : mesh.tri) {
        for (double c : facetNormal(t)) f32(c);
        for (long long k : t)
            for (double c : mesh.p[k]) f32(c);
        bin.append(2, '\0');
    }
    return bin;
}

int usage() {
    std::fprintf(stderr,
                 "usage: glint_gen_mesh [--segments N] [--sides N] [--uv] [--ascii] "
                 "[--big-endian] OUT.obj|OUT.glb|OUT.ply|OUT.stl\n");
    return 2;
}

}  // namespace

int main(int argc, char** argv) {
    long long segments = 2048, sides = 256;
    bool uv = false, ascii = false, bigEndian = false;
    std::string path;
    for (int i = 1; i < argc; ++i) {
        std::string_view a = argv[i];
        if ((a == "--segments" || a == "--sides") && i + 1 < argc) {
            long long v = std::atoll(argv[++i]);
            if (v < 3 || v > 100000) return usage();
            (a == "--segments" ? segments : sides) = v;
        } else if (a == "--uv") {
            uv = true;
        } else if (a == "--ascii") {
            ascii = true;
        } else if (a == "--big-endian") {
            bigEndian = true;
        } else if (!a.empty() && a[0] != '-' && path.empty()) {
            path = a;
        } else {
            return usage();
        }
    }
    if (path.empty()) return usage();

    // With texture coordinates the seams need their own vertices (u = 1, v = 1).
    const long long columns = segments + (uv ? 1 : 0), rows = sides + (uv ? 1 : 0);
    Mesh mesh;
    for (long long i = 0; i < columns; ++i)
        for (long long j = 0; j < rows; ++j) {
            double t = kTwoPi * static_cast<double>(i) / static_cast<double>(segments);
            double s = kTwoPi * static_cast<double>(j) / static_cast<double>(sides);
            mesh.p.push_back(surface(t, s));
            mesh.n.push_back(surfaceNormal(t, s));
            if (uv)
                mesh.uv.push_back({static_cast<double>(i) / static_cast<double>(segments),
                                   static_cast<double>(j) / static_cast<double>(sides)});
        }
    // Vertex (i, j) is number i * rows + j (from 0); cells wrap around both ways without --uv.
    auto index = [&](long long i, long long j) {
        if (!uv) i %= segments, j %= sides;
        return i * rows + j;
    };
    for (long long i = 0; i < segments; ++i)
        for (long long j = 0; j < sides; ++j) {
            long long a = index(i, j), b = index(i + 1, j), c = index(i + 1, j + 1),
                      d = index(i, j + 1);
            // Counter-clockwise seen from outside: around the tube, s turns left-handed about
            // the knot's tangent, so the outward normal is ds x dt and the cell (a, b, c, d)
            // runs clockwise seen from outside; its triangles are listed the other way round.
            mesh.tri.push_back({a, c, b});
            mesh.tri.push_back({a, d, c});
        }

    std::string_view name = path;
    std::string_view ext = name.size() >= 4 ? name.substr(name.size() - 4) : "";
    std::string bytes = ext == ".glb"   ? glbFile(mesh)
                        : ext == ".ply" ? plyFile(mesh, ascii, bigEndian)
                        : ext == ".stl" ? stlFile(mesh, ascii)
                                        : objText(mesh);
    FILE* f = std::fopen(path.c_str(), "wb");
    if (!f || std::fwrite(bytes.data(), 1, bytes.size(), f) != bytes.size() ||
        std::fclose(f) != 0) {
        std::perror(path.c_str());
        return 1;
    }
    std::printf("%s: %zu vertices, %zu triangles, %.1f MB\n", path.c_str(), mesh.p.size(),
                mesh.tri.size(), static_cast<double>(bytes.size()) / 1e6);
    return 0;
}
