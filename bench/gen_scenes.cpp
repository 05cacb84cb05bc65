// glint_bench_scenes OUTDIR: writes the whole-render benchmark scenes of issue 3, each twice:
// NAME.test in Glint's CSE167x format and NAME.pov for POV-Ray 3.7, describing the same image.
//
//   spheres  1000 spheres on a reflective ground, one point light, one reflection bounce
//   mirrors  five mirror spheres on a checker floor, two point lights, five bounces
//   torus    the 1M-triangle rippled torus of bench/torus.h on its ground, shadows, no bounce
//
// How the two descriptions correspond (the same in every scene):
// - Camera: Glint's `camera` takes the vertical field of view, POV-Ray's `angle` the horizontal
//   one; both are written from the same numbers (tan(fovx/2) = tan(fovy/2) * 1280 / 720).
//   Glint's camera is right-handed (gluLookAt), POV-Ray's is left-handed, so the POV-Ray camera
//   uses `right -x*aspect` to give the same, unmirrored image.
// - Materials: Glint's ambient A, diffuse D, specular S (grey), shininess n become a POV-Ray
//   pigment D with finish `ambient a diffuse 1 specular S roughness 1/n reflection S`, where
//   A = a * D. Glint uses S both for the Blinn-Phong highlight and as the mirror weight, so every
//   surface with a highlight reflects, in both files. POV-Ray's highlight is
//   specular * (N.H)^(1/roughness), Glint's S * (N.H)^n: the same.
// - Lights: point lights without attenuation (Glint's default `attenuation 1 0 0`, POV-Ray with
//   no fade), shadows on both sides; no area lights, radiosity or photons.
// - Bounces: Glint's `maxdepth d` traces up to d mirror rays after the camera ray; POV-Ray's
//   `max_trace_level` counts the camera ray too, so it is d + 1. `adc_bailout 0` stops POV-Ray
//   from cutting reflection trees short where Glint would trace them.
// - Colours stay linear: `assumed_gamma 1.0` (render with File_Gamma=1.0 to compare images).
// - Rays that hit nothing get the same constant background colour.

#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "torus.h"

namespace {

using glint::bench::Mesh;
using glint::bench::View;
using Vec3 = std::array<double, 3>;

constexpr int kWidth = 1280, kHeight = 720;

// ---------------------------------------------------------------------------------------------
// Fast text output: everything goes into one string, numbers through std::to_chars.

class Text {
  public:
    Text& operator<<(std::string_view s) {
        buf_.append(s);
        return *this;
    }
    Text& operator<<(char c) {
        buf_.push_back(c);
        return *this;
    }
    /// 15 significant digits: exact for the scenes' short decimals, without the noise of
    /// products such as 0.2 * 0.45 = 0.09000000000000001.
    Text& num(double v) {
        char tmp[32];
        auto r = std::to_chars(tmp, tmp + sizeof tmp, v, std::chars_format::general, 15);
        buf_.append(tmp, r.ptr);
        return *this;
    }
    /// Shortest decimal that reads back as the same float: Glint stores geometry in float, so
    /// mesh vertices are rounded to float once here and both renderers read identical values.
    Text& fnum(double v) {
        char tmp[32];
        auto r = std::to_chars(tmp, tmp + sizeof tmp, static_cast<float>(v));
        buf_.append(tmp, r.ptr);
        return *this;
    }
    Text& integer(uint64_t v) {
        char tmp[24];
        auto r = std::to_chars(tmp, tmp + sizeof tmp, v);
        buf_.append(tmp, r.ptr);
        return *this;
    }
    /// "x y z" (Glint) with the given separator.
    Text& vec(const Vec3& v, std::string_view sep = " ") {
        num(v[0]) << sep;
        num(v[1]) << sep;
        return num(v[2]);
    }
    /// "<x, y, z>" (POV-Ray).
    Text& pov(const Vec3& v) {
        *this << '<';
        vec(v, ", ");
        return *this << '>';
    }
    void reserve(size_t n) { buf_.reserve(n); }

    void writeTo(const std::filesystem::path& path) const {
        std::FILE* f = std::fopen(path.c_str(), "wb");
        if (!f) throw std::runtime_error("cannot create " + path.string());
        bool ok = std::fwrite(buf_.data(), 1, buf_.size(), f) == buf_.size();
        ok = (std::fclose(f) == 0) && ok;
        if (!ok) throw std::runtime_error("cannot write " + path.string());
    }

  private:
    std::string buf_;
};

// ---------------------------------------------------------------------------------------------
// The shared description of a scene.

struct Material {
    Vec3 diffuse;
    double ambient = 0.1;  ///< Glint's ambient colour is ambient * diffuse.
    double specular = 0;   ///< Grey highlight colour and mirror weight.
    double shininess = 1;  ///< Blinn-Phong exponent.
};

struct Light {
    Vec3 position, colour;
};

struct Camera {
    Vec3 eye, at, up{0, 1, 0};
    double fovyDegrees;

    double fovxDegrees() const {
        double t = std::tan(fovyDegrees * std::numbers::pi / 360) * kWidth / kHeight;
        return 2 * std::atan(t) * 180 / std::numbers::pi;
    }
};

struct Header {
    std::string_view name, correspondence;
    Camera camera;
    std::vector<Light> lights;
    int maxDepth;
    Vec3 background;
};

Vec3 scaled(const Vec3& v, double s) { return {v[0] * s, v[1] * s, v[2] * s}; }

void glintMaterial(Text& t, const Material& m) {
    t << "ambient ";
    t.vec(scaled(m.diffuse, m.ambient)) << "\ndiffuse ";
    t.vec(m.diffuse) << "\nspecular ";
    t.vec({m.specular, m.specular, m.specular}) << "\nshininess ";
    t.num(m.shininess) << '\n';
}

/// A POV-Ray texture body (without the `texture { }` around it).
void povTextureBody(Text& t, const Material& m) {
    t << "pigment { rgb ";
    t.pov(m.diffuse) << " } finish { ambient ";
    t.num(m.ambient) << " diffuse 1";
    if (m.specular != 0) {
        t << " specular ";
        t.num(m.specular) << " roughness ";
        t.num(1 / m.shininess) << " reflection { ";
        t.num(m.specular) << " }";
    } else {
        t << " specular 0 reflection { 0 }";
    }
    t << " }";
}

void povDeclareTexture(Text& t, std::string_view name, const Material& m) {
    t << "#declare " << name << " = texture { ";
    povTextureBody(t, m);
    t << " }\n";
}

/// Comment lines: each line of `text` prefixed with `prefix`.
void comment(Text& t, std::string_view prefix, std::string_view text) {
    while (!text.empty()) {
        auto nl = text.find('\n');
        auto line = text.substr(0, nl);
        t << prefix;
        if (!line.empty()) t << ' ' << line;
        t << '\n';
        text = nl == std::string_view::npos ? std::string_view{} : text.substr(nl + 1);
    }
}

void glintHeader(Text& t, const Header& h) {
    comment(t, "#", h.correspondence);
    t << "# Glint side: render with `glint --spp N`; the POV-Ray twin is " << h.name << ".pov.\n\n";
    t << "size ";
    t.integer(kWidth) << ' ';
    t.integer(kHeight) << "\nmaxdepth ";
    t.integer(static_cast<uint64_t>(h.maxDepth)) << "\ncamera ";
    t.vec(h.camera.eye) << "  ";
    t.vec(h.camera.at) << "  ";
    t.vec(h.camera.up) << "  ";
    t.num(h.camera.fovyDegrees) << "\nbackground ";
    t.vec(h.background) << "\n";
    for (const auto& l : h.lights) {
        t << "point ";
        t.vec(l.position) << "  ";
        t.vec(l.colour) << '\n';
    }
    t << "emission 0 0 0\n\n";
}

void povHeader(Text& t, const Header& h) {
    comment(t, "//", h.correspondence);
    t << "// POV-Ray side: render at +W1280 +H720; the Glint twin is " << h.name << ".test.\n\n";
    t << "#version 3.7;\nglobal_settings {\n  assumed_gamma 1.0\n  ambient_light rgb 1\n  "
         "max_trace_level ";
    t.integer(static_cast<uint64_t>(h.maxDepth + 1)) << "  // Glint maxdepth ";
    t.integer(static_cast<uint64_t>(h.maxDepth)) << " + the camera ray\n  adc_bailout 0\n}\n";
    t << "camera {\n  perspective\n  location ";
    t.pov(h.camera.eye) << "\n  look_at ";
    t.pov(h.camera.at) << "\n  sky ";
    t.pov(h.camera.up) << "\n  right -x * 1280 / 720  // right-handed, as Glint\n  up y\n  angle ";
    t.num(h.camera.fovxDegrees()) << "  // horizontal; Glint's vertical fov is ";
    t.num(h.camera.fovyDegrees) << "\n}\nbackground { rgb ";
    t.pov(h.background) << " }\n";
    for (const auto& l : h.lights) {
        t << "light_source { ";
        t.pov(l.position) << " color rgb ";
        t.pov(l.colour) << " }\n";
    }
    t << '\n';
}

/// A square on y = 0 from (-half, -half) to (half, half) in x and z as two triangles facing +y,
/// in the vertex order of addGround() in torus.h.
constexpr std::array<std::array<int, 2>, 4> kSquareCorners{{{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}};
constexpr std::array<std::array<int, 3>, 2> kSquareTriangles{{{0, 2, 1}, {0, 3, 2}}};

// ---------------------------------------------------------------------------------------------
// spheres: 1000 spheres on a reflective ground, one light, one bounce.

/// A small deterministic generator, so the scene never changes.
class Lcg {
  public:
    double uniform() {
        state_ = state_ * 6364136223846793005ULL + 1442695040888963407ULL;
        return static_cast<double>(state_ >> 11) * 0x1.0p-53;
    }

  private:
    uint64_t state_ = 0x9e3779b97f4a7c15ULL;
};

void writeSpheres(const std::filesystem::path& dir) {
    const Header h{
        "spheres",
        "Benchmark scene `spheres` (issue 3): 1000 spheres on a reflective ground, one point\n"
        "light, one reflection bounce, 1280x720.\n"
        "The ground is the same square of two triangles, 2000 units across, in both files (not\n"
        "an infinite plane, which Glint's format lacks). The spheres rest on it in a 40 x 25 grid\n"
        "with random radii and offsets and one of 8 materials. Every material has a grey\n"
        "specular colour, which Glint also uses as its mirror weight: POV-Ray's finish has the\n"
        "same value as `reflection`. Glint maxdepth 1 = POV-Ray max_trace_level 2.",
        {{0, 11, -30}, {0, 0, 1}, {0, 1, 0}, 32},
        {{{-15, 30, -25}, {1, 1, 1}}},
        1,
        {0.55, 0.65, 0.85}};

    const std::array<Material, 8> palette{{
        {{0.8, 0.15, 0.1}, 0.1, 0.3, 40},
        {{0.1, 0.5, 0.85}, 0.1, 0.3, 40},
        {{0.9, 0.75, 0.2}, 0.1, 0.3, 40},
        {{0.2, 0.7, 0.25}, 0.1, 0.3, 40},
        {{0.75, 0.3, 0.75}, 0.1, 0.3, 40},
        {{0.9, 0.9, 0.9}, 0.1, 0.3, 40},
        {{0.05, 0.05, 0.05}, 0.1, 0.8, 200},
        {{0.95, 0.5, 0.15}, 0.1, 0.3, 40},
    }};
    const Material ground{{0.45, 0.45, 0.45}, 0.2, 0.5, 60};

    struct Ball {
        Vec3 centre;
        double radius;
        size_t material;
    };
    std::vector<Ball> balls;
    Lcg rng;
    constexpr int kCols = 40, kRows = 25;
    constexpr double kSpacing = 1.1;
    for (int row = 0; row < kRows; ++row)
        for (int col = 0; col < kCols; ++col) {
            double r = 0.22 + 0.28 * rng.uniform();
            double slack = kSpacing / 2 - r;  // keeps neighbours apart
            double x = (col - (kCols - 1) / 2.0) * kSpacing + slack * (2 * rng.uniform() - 1);
            double z = (row - (kRows - 1) / 2.0) * kSpacing + slack * (2 * rng.uniform() - 1);
            auto m = static_cast<size_t>(rng.uniform() * palette.size()) % palette.size();
            balls.push_back({{x, r, z}, r, m});
        }

    constexpr double kGroundHalf = 1000;
    Text g, p;
    glintHeader(g, h);
    povHeader(p, h);

    g << "# The ground: a square of two triangles.\n";
    glintMaterial(g, ground);
    g << "maxverts 4\n";
    for (auto [sx, sz] : kSquareCorners) {
        g << "vertex ";
        g.vec({sx * kGroundHalf, 0, sz * kGroundHalf}) << '\n';
    }
    for (auto [a, b, c] : kSquareTriangles) {
        g << "tri ";
        g.integer(static_cast<uint64_t>(a)) << ' ';
        g.integer(static_cast<uint64_t>(b)) << ' ';
        g.integer(static_cast<uint64_t>(c)) << '\n';
    }

    p << "// The ground: the same square of two triangles.\nmesh {\n";
    for (auto [a, b, c] : kSquareTriangles) {
        p << "  triangle { ";
        for (int k : {a, b, c}) {
            auto [sx, sz] = kSquareCorners[static_cast<size_t>(k)];
            p.pov({sx * kGroundHalf, 0, sz * kGroundHalf});
            if (k != c) p << ", ";
        }
        p << " }\n";
    }
    p << "  texture { ";
    povTextureBody(p, ground);
    p << " }\n}\n\n// The palette.\n";
    for (size_t i = 0; i < palette.size(); ++i) {
        const char name[] = {'T', static_cast<char>('0' + i), '\0'};  // 8 entries: one digit
        povDeclareTexture(p, name, palette[i]);
    }

    g << "\n# 1000 spheres.\n";
    p << "\n// 1000 spheres.\n";
    size_t current = palette.size();
    for (const Ball& b : balls) {
        if (b.material != current) {
            glintMaterial(g, palette[b.material]);
            current = b.material;
        }
        g << "sphere ";
        g.vec(b.centre) << ' ';
        g.num(b.radius) << '\n';
        p << "sphere { ";
        p.pov(b.centre) << ", ";
        p.num(b.radius) << " texture { T";
        p.integer(b.material) << " } }\n";
    }
    g.writeTo(dir / "spheres.test");
    p.writeTo(dir / "spheres.pov");
}

// ---------------------------------------------------------------------------------------------
// mirrors: five mirror spheres on a checker floor, two lights, five bounces.

void writeMirrors(const std::filesystem::path& dir) {
    constexpr int kTiles = 40;     // tiles per side (even)
    constexpr double kTile = 1.0;  // tile size
    constexpr double kHalf = kTiles * kTile / 2;
    const Header h{
        "mirrors",
        "Benchmark scene `mirrors` (issue 3): five mirror spheres on a checker floor, two point\n"
        "lights, five reflection bounces, 1280x720.\n"
        "The floor is a 40 x 40 checkerboard of unit tiles on y = 0, 40 units across. Glint's\n"
        "format has no textures: there it is 3200 triangles in two alternating materials.\n"
        "POV-Ray draws the same square as two triangles with a `checker` texture of the same two\n"
        "materials (scaled to the tile, moved half a tile up so y = 0 is not a cell boundary):\n"
        "the same tiles, colours and extent. The floor does not reflect (specular 0); the\n"
        "spheres do. Glint maxdepth 5 = POV-Ray max_trace_level 6.",
        {{0, 2.9, -7.8}, {0, 0.9, 0}, {0, 1, 0}, 40},
        {{{6, 9, -7}, {0.75, 0.72, 0.65}}, {{-7, 5, -3}, {0.35, 0.38, 0.5}}},
        5,
        {0.55, 0.65, 0.85}};

    const Material light{{0.8, 0.8, 0.76}, 0.15, 0, 1};
    const Material dark{{0.15, 0.18, 0.25}, 0.15, 0, 1};
    const std::array<Material, 5> mirror{{
        {{0.05, 0.05, 0.05}, 0.4, 0.9, 300},
        {{0.3, 0.05, 0.03}, 0.4, 0.7, 150},
        {{0.03, 0.1, 0.3}, 0.4, 0.7, 150},
        {{0.25, 0.2, 0.02}, 0.4, 0.75, 150},
        {{0.03, 0.25, 0.06}, 0.4, 0.7, 150},
    }};
    const std::array<std::array<double, 4>, 5> balls{{
        {0, 1.3, 0.3, 1.3},
        {-2.6, 0.8, -1.3, 0.8},
        {2.6, 0.8, -1.3, 0.8},
        {-1.9, 0.7, 2.1, 0.7},
        {1.9, 0.7, 2.1, 0.7},
    }};

    Text g, p;
    glintHeader(g, h);
    povHeader(p, h);

    // Glint: the board as (kTiles + 1)^2 shared vertices and two triangles per tile. With the
    // POV-Ray texture below, tile (i, k) is POV-Ray's first texture when i + k is odd.
    g << "# The floor: a checkerboard of triangles, " << std::to_string(2 * kTiles * kTiles)
      << " in all.\nmaxverts " << std::to_string((kTiles + 1) * (kTiles + 1)) << '\n';
    for (int k = 0; k <= kTiles; ++k)
        for (int i = 0; i <= kTiles; ++i) {
            g << "vertex ";
            g.vec({i * kTile - kHalf, 0, k * kTile - kHalf}) << '\n';
        }
    auto id = [](int i, int k) { return static_cast<uint64_t>(k * (kTiles + 1) + i); };
    for (int parity : {1, 0}) {
        glintMaterial(g, parity == 1 ? light : dark);
        for (int k = 0; k < kTiles; ++k)
            for (int i = 0; i < kTiles; ++i) {
                if ((i + k) % 2 != parity) continue;
                uint64_t a = id(i, k), b = id(i, k + 1), c = id(i + 1, k + 1), d = id(i + 1, k);
                g << "tri ";
                g.integer(a) << ' ';
                g.integer(b) << ' ';
                g.integer(c) << "\ntri ";
                g.integer(a) << ' ';
                g.integer(c) << ' ';
                g.integer(d) << '\n';
            }
    }

    p << "// The floor: the same square, two triangles with a checker texture.\n";
    povDeclareTexture(p, "Light", light);
    povDeclareTexture(p, "Dark", dark);
    p << "mesh {\n";
    for (auto [a, b, c] : kSquareTriangles) {
        p << "  triangle { ";
        for (int k : {a, b, c}) {
            auto [sx, sz] = kSquareCorners[static_cast<size_t>(k)];
            p.pov({sx * kHalf, 0, sz * kHalf});
            if (k != c) p << ", ";
        }
        p << " }\n";
    }
    p << "  texture { checker texture { Light } texture { Dark } scale ";
    p.num(kTile) << " translate <0, ";
    p.num(kTile / 2) << ", 0> }\n}\n";

    g << "\n# Five mirror spheres.\n";
    p << "\n// Five mirror spheres.\n";
    for (size_t i = 0; i < balls.size(); ++i) {
        const auto& b = balls[i];
        glintMaterial(g, mirror[i]);
        g << "sphere ";
        g.vec({b[0], b[1], b[2]}) << ' ';
        g.num(b[3]) << '\n';
        p << "sphere { ";
        p.pov({b[0], b[1], b[2]}) << ", ";
        p.num(b[3]) << " texture { ";
        povTextureBody(p, mirror[i]);
        p << " } }\n";
    }
    g.writeTo(dir / "mirrors.test");
    p.writeTo(dir / "mirrors.pov");
}

// ---------------------------------------------------------------------------------------------
// torus: the 1M-triangle mesh of torus.h on its ground, shadows, no reflections.

/// Whether the torus's first triangle has its normal (B-A) x (C-A) pointing towards the tube's
/// centre line (the circle of radius R = 1 in the plane of the vertices' mean height).
bool facesInwards(const Mesh& m) {
    const auto& t = m.triangles.front();
    const Vec3 &a = m.vertices[t[0]], &b = m.vertices[t[1]], &c = m.vertices[t[2]];
    Vec3 e1{b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e2{c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    Vec3 n{e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
           e1[0] * e2[1] - e1[1] * e2[0]};
    double meanY = 0;
    for (const auto& v : m.vertices) meanY += v[1];
    meanY /= static_cast<double>(m.vertices.size());
    double angle = std::atan2(a[2], a[0]);
    Vec3 out{a[0] - std::cos(angle), a[1] - meanY, a[2] - std::sin(angle)};
    return n[0] * out[0] + n[1] * out[1] + n[2] * out[2] < 0;
}

void writeTorus(const std::filesystem::path& dir) {
    const View view;
    Mesh mesh = glint::bench::rippledTorus();
    const size_t torusVertices = mesh.vertices.size(), torusTriangles = mesh.triangles.size();
    // Glint never flips a triangle's normal (B-A) x (C-A) towards the viewer, so it lights only
    // the side that normal points to; POV-Ray lights whichever side it sees. torus.h's winding
    // gives normals pointing into the tube, which would leave Glint's torus black and without
    // shadow rays: turn the triangles around when they face inwards. Same triangles, same
    // vertices, for both renderers.
    if (facesInwards(mesh)) {
        for (size_t i = 0; i < torusTriangles; ++i)
            std::swap(mesh.triangles[i][1], mesh.triangles[i][2]);
    }
    glint::bench::addGround(mesh);

    const Header h{
        "torus",
        "Benchmark scene `torus` (issue 3): the rippled torus of bench/torus.h, 1,000,000 flat\n"
        "triangles, on its ground square (two more triangles), lit by one point light with\n"
        "shadows, no reflections (both materials have specular 0; Glint maxdepth 0 = POV-Ray\n"
        "max_trace_level 1), 1280x720, the camera of torus.h's View.\n"
        "Glint reads the vertices and triangles as `vertex` and `tri` lines (the torus's, then\n"
        "the ground's two after a material change); POV-Ray reads the same vertices (the same\n"
        "decimal strings) and faces as a `mesh2` for the torus and a `mesh2` for the ground.\n"
        "Vertices are rounded to float (Glint's storage) before printing. The torus triangles\n"
        "are wound so that Glint's normal (B-A) x (C-A) points out of the tube (torus.h's order\n"
        "points it in, and Glint does not flip normals; POV-Ray does not care).",
        {view.eye, view.at, view.up, view.fovyDegrees()},
        {{view.light, {1, 1, 1}}},
        0,
        {0.55, 0.65, 0.85}};
    const Material torus{{0.85, 0.5, 0.2}, 0.12, 0, 1};
    const Material ground{{0.6, 0.6, 0.55}, 0.15, 0, 1};

    Text g, p;
    g.reserve(40u << 20);
    p.reserve(40u << 20);
    glintHeader(g, h);
    povHeader(p, h);

    g << "maxverts ";
    g.integer(mesh.vertices.size()) << '\n';
    for (const auto& v : mesh.vertices) {
        g << "vertex ";
        g.fnum(v[0]) << ' ';
        g.fnum(v[1]) << ' ';
        g.fnum(v[2]) << '\n';
    }
    for (size_t i = 0; i < mesh.triangles.size(); ++i) {
        if (i == 0) glintMaterial(g, torus);
        if (i == torusTriangles) glintMaterial(g, ground);
        const auto& t = mesh.triangles[i];
        g << "tri ";
        g.integer(t[0]) << ' ';
        g.integer(t[1]) << ' ';
        g.integer(t[2]) << '\n';
    }

    auto povMesh = [&](size_t v0, size_t v1, size_t t0, size_t t1, const Material& m) {
        p << "mesh2 {\n  vertex_vectors {\n    ";
        p.integer(v1 - v0);
        for (size_t i = v0; i < v1; ++i) {
            const auto& v = mesh.vertices[i];
            p << ",\n    <";
            p.fnum(v[0]) << ',';
            p.fnum(v[1]) << ',';
            p.fnum(v[2]) << '>';
        }
        p << "\n  }\n  face_indices {\n    ";
        p.integer(t1 - t0);
        for (size_t i = t0; i < t1; ++i) {
            const auto& t = mesh.triangles[i];
            p << ",\n    <";
            p.integer(t[0] - v0) << ',';
            p.integer(t[1] - v0) << ',';
            p.integer(t[2] - v0) << '>';
        }
        p << "\n  }\n  texture { ";
        povTextureBody(p, m);
        p << " }\n}\n";
    };
    p << "// The torus.\n";
    povMesh(0, torusVertices, 0, torusTriangles, torus);
    p << "// The ground.\n";
    povMesh(torusVertices, mesh.vertices.size(), torusTriangles, mesh.triangles.size(), ground);

    g.writeTo(dir / "torus.test");
    p.writeTo(dir / "torus.pov");
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr,
                     "usage: %s OUTDIR\nwrites spheres, mirrors and torus as OUTDIR/NAME.test "
                     "(Glint) and OUTDIR/NAME.pov (POV-Ray)\n",
                     argv[0]);
        return 2;
    }
    try {
        std::filesystem::path dir(argv[1]);
        std::filesystem::create_directories(dir);
        writeSpheres(dir);
        writeMirrors(dir);
        writeTorus(dir);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "glint_bench_scenes: error: %s\n", e.what());
        return 1;
    }
    return 0;
}
