#include "glint/io/hw3_loader.h"

#include <sys/stat.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <system_error>

#include "glint/core/system.h"
#include "glint/geometry/polygon.h"
#include "glint/io/image_io.h"
#include "glint/io/mapped_file.h"
#include "glint/io/numbers.h"

namespace glint {
namespace {

struct Token {
    std::string_view text;
    int column = 0;
};

class Parser;
using Handler = void (Parser::*)();

struct Command {
    std::string_view name;
    int minArgs, maxArgs;
    std::string_view usage;  ///< Argument names for messages.
    Handler handler;
};

/// Most vertices a `polygon` takes (ear clipping takes time quadratic in the count).
constexpr int kMaxPolygonVertices = 1024;
/// Lines hold at most this many tokens (a polygon and one more, to point at the first extra
/// argument); more is always an argument-count error.
constexpr int kMaxTokens = kMaxPolygonVertices + 2;
/// A `maxverts` bound is only a hint: never reserve more than this many vertices from it.
constexpr long long kMaxVertexReserve = 1 << 20;

class Parser {
  public:
    Parser(std::string_view text, const std::string& file, std::vector<Diagnostic>& warnings,
           const LoadLimits& limits)
        : text_(text),
          file_(file),
          warnings_(warnings),
          limits_(limits),
          scene_(std::make_unique<Scene>()) {}

    std::unique_ptr<Scene> run();
    static const std::vector<Command>& commands();

  private:
    // Lexing and diagnostics.
    void tokenize(std::string_view line);
    FileLoc loc(int column) const { return {file_, line_, column}; }
    [[noreturn]] void fail(int token, const std::string& message) const {
        throw SceneError(loc(tok_[token].column), message);
    }
    void warn(int token, const std::string& message) {
        warnings_.push_back({loc(tok_[token].column), message});
    }
    std::string quoted(int token) const {
        std::string q(1, '\'');  // built by appending: GCC 12 warns falsely on "'" + string
        q.append(tok_[token].text).push_back('\'');
        return q;
    }

    // Arguments.
    double number(int i) const;
    double real(int i) const;
    long long integer(int i, long long lo, long long hi) const;
    Vec3 vec3(int i) const { return {real(i), real(i + 1), real(i + 2)}; }
    Vec3 colour(int i) const { return vec3(i); }
    /// The current transform, baked; fails at the command if it is singular. The common case,
    /// already baked, stays inline (tri lines call it millions of times).
    const Transform& transform() {
        if (transformValid_ && transform_) return *transform_;
        return bakeTransform();
    }
    const Transform& bakeTransform();
    /// The id of the current material, added to the scene when it changed since last asked.
    uint32_t material() {
        if (materialChanged_)
            materialId_ = scene_->addMaterial(material_), materialChanged_ = false;
        return materialId_;
    }
    /// Argument `i` as an index into a pile of `count` entries, named `one` / `many`.
    uint32_t vertexIndex(int i, size_t count, const char* one, const char* many) const;
    static bool inRange(const Vec3& p) {
        return std::abs(p.x) <= kMaxCoordinate && std::abs(p.y) <= kMaxCoordinate &&
               std::abs(p.z) <= kMaxCoordinate;
    }
    /// `p`, a transformed vertex named by argument `i`, if it is within the coordinate range.
    Vec3 checkedVertex(const Vec3& p, int i) const {
        if (!inRange(p))
            fail(i, "vertex " + quoted(i) +
                        " lies beyond the supported coordinate range (1e18) after the transform");
        return p;
    }

    // Commands.
    void cmdSize();
    void cmdMaxDepth();
    void cmdOutput();
    void cmdCamera();
    void cmdSphere();
    void cmdMaxVerts();
    void cmdMaxVertNorms();
    void cmdVertex();
    void cmdVertexNormal();
    void cmdTri();
    void cmdTriNormal();
    void cmdTranslate();
    void cmdRotate();
    void cmdScale();
    void cmdPushTransform();
    void cmdPopTransform();
    void cmdDirectional();
    void cmdPoint();
    void cmdAttenuation();
    void cmdAmbient() {
        material_.ambient = colour(1);
        materialChanged_ = true;
    }
    void cmdDiffuse() {
        material_.diffuse = colour(1);
        materialChanged_ = true;
    }
    void cmdSpecular() {
        material_.specular = colour(1);
        materialChanged_ = true;
    }
    void cmdEmission() {
        material_.emission = colour(1);
        materialChanged_ = true;
    }
    void cmdShininess();
    void cmdBackground();
    // Extensions beyond Whitted (docs/scene-format.md).
    void cmdTransmission() {
        material_.transmission = colour(1);
        materialChanged_ = true;
    }
    void cmdIor();
    void cmdRoughness();
    void cmdQuadLight();
    void cmdLightSamples() { scene_->lightSamples = static_cast<int>(integer(1, 1, 64)); }
    void cmdSpp() { scene_->spp = static_cast<int>(integer(1, 1, 65536)); }
    void cmdFilter();
    void cmdLens();
    // The shape extensions (docs/scene-format.md).
    void cmdPlane();
    void cmdBox();
    void cmdCylinder();
    void cmdCone();
    void cmdDisk();
    void cmdPolygon();
    /// Adds a box, cylinder, cone or disk placed by `objectFromCanonical` under the current
    /// transform, after checking it against the coordinate limits.
    void addShape(ShapeKind kind, const Mat4& objectFromCanonical, double k, const char* name);

    void addTriangle(const Vec3 (&p)[3], const Vec3* normals) {
        if (!scene_->primitives.addTriangle(p[0], p[1], p[2], normals, material()) &&
            !warnedDegenerate_) {
            warn(0, "triangle has zero area and is skipped (later ones are skipped silently)");
            warnedDegenerate_ = true;
        }
    }
    void applyTransform(const Mat4& m) {
        stack_.back() = stack_.back() * m;
        transformValid_ = false;
    }
    void unknownCommand();

    std::string_view text_;
    const std::string& file_;
    std::vector<Diagnostic>& warnings_;
    LoadLimits limits_;
    std::unique_ptr<Scene> scene_;

    int line_ = 0;
    std::array<Token, kMaxTokens> tok_;
    int ntok_ = 0;  ///< Tokens on the line, possibly more than kMaxTokens (only those are kept).

    std::vector<Mat4> stack_{Mat4::identity()};
    std::optional<Transform> transform_;  ///< stack_.back() baked; empty if singular.
    bool transformValid_ = false;
    Material material_;
    bool materialChanged_ = true;
    uint32_t materialId_ = 0;
    Vec3 attenuation_{1, 0, 0};
    LargeVector<Vec3> vertices_;
    std::vector<std::array<Vec3, 2>> normalVertices_;  ///< Position and unit normal (or zero).
    long long maxVerts_ = -1, maxVertNorms_ = -1;
    bool warnedVerts_ = false, warnedVertNorms_ = false, warnedDegenerate_ = false;
    int cameraLine_ = 0;
    double apertureRadius_ = 0, focusDistance_ = 0;  ///< From `lens`, applied to the camera.
};

const std::vector<Command>& Parser::commands() {
    // The most frequent commands first: lookup is a linear scan.
    static const std::vector<Command> table = {
        {"vertex", 3, 3, "x y z", &Parser::cmdVertex},
        {"tri", 3, 3, "v1 v2 v3", &Parser::cmdTri},
        {"sphere", 4, 4, "x y z radius", &Parser::cmdSphere},
        {"pushTransform", 0, 0, "", &Parser::cmdPushTransform},
        {"popTransform", 0, 0, "", &Parser::cmdPopTransform},
        {"translate", 3, 3, "x y z", &Parser::cmdTranslate},
        {"rotate", 4, 4, "x y z degrees", &Parser::cmdRotate},
        {"scale", 3, 3, "x y z", &Parser::cmdScale},
        {"vertexnormal", 6, 6, "x y z nx ny nz", &Parser::cmdVertexNormal},
        {"trinormal", 3, 3, "v1 v2 v3", &Parser::cmdTriNormal},
        {"ambient", 3, 3, "r g b", &Parser::cmdAmbient},
        {"diffuse", 3, 3, "r g b", &Parser::cmdDiffuse},
        {"specular", 3, 3, "r g b", &Parser::cmdSpecular},
        {"emission", 3, 3, "r g b", &Parser::cmdEmission},
        {"shininess", 1, 1, "s", &Parser::cmdShininess},
        {"size", 2, 2, "width height", &Parser::cmdSize},
        {"maxdepth", 1, 1, "depth", &Parser::cmdMaxDepth},
        {"output", 1, 1, "filename", &Parser::cmdOutput},
        {"camera", 10, 10, "fromx fromy fromz atx aty atz upx upy upz fovy", &Parser::cmdCamera},
        {"maxverts", 1, 1, "count", &Parser::cmdMaxVerts},
        {"maxvertnorms", 1, 1, "count", &Parser::cmdMaxVertNorms},
        {"directional", 6, 6, "x y z r g b", &Parser::cmdDirectional},
        {"point", 6, 6, "x y z r g b", &Parser::cmdPoint},
        {"attenuation", 3, 3, "constant linear quadratic", &Parser::cmdAttenuation},
        {"background", 3, 6, "r g b [r2 g2 b2]", &Parser::cmdBackground},
        {"transmission", 3, 3, "r g b", &Parser::cmdTransmission},
        {"ior", 1, 1, "index", &Parser::cmdIor},
        {"roughness", 1, 1, "alpha", &Parser::cmdRoughness},
        {"quadLight", 12, 12, "x y z e1x e1y e1z e2x e2y e2z r g b", &Parser::cmdQuadLight},
        {"lightsamples", 1, 1, "n", &Parser::cmdLightSamples},
        {"spp", 1, 1, "samples", &Parser::cmdSpp},
        {"filter", 1, 2, "box|gaussian [radius]", &Parser::cmdFilter},
        {"lens", 1, 2, "aperture-radius [focus-distance]", &Parser::cmdLens},
        {"plane", 6, 6, "px py pz nx ny nz", &Parser::cmdPlane},
        {"box", 6, 6, "x0 y0 z0 x1 y1 z1", &Parser::cmdBox},
        {"cylinder", 7, 7, "x0 y0 z0 x1 y1 z1 radius", &Parser::cmdCylinder},
        {"cone", 8, 8, "x0 y0 z0 r0 x1 y1 z1 r1", &Parser::cmdCone},
        {"disk", 7, 7, "cx cy cz nx ny nz radius", &Parser::cmdDisk},
        {"polygon", 3, kMaxPolygonVertices, "v1 v2 v3 ...", &Parser::cmdPolygon},
    };
    return table;
}

/// Upper bounds of the primitives and vertices a scene text creates, from its lines' first
/// words: enough to reserve storage once instead of growing it (and copying) many times.
struct Counts {
    size_t triangles = 0, spheres = 0, shapes = 0, vertices = 0;
    size_t polygonTriangles = 0;  ///< Part of `triangles`; these carry shading normals.
};

/// Blank-separated words on the line from `p` to `end`, up to a comment.
size_t wordsOnLine(const char* p, const char* end) {
    size_t n = 0;
    bool inWord = false;
    for (; p < end && *p != '\n' && *p != '#'; ++p) {
        bool blank = *p == ' ' || *p == '\t' || *p == '\r' || *p == '\v' || *p == '\f';
        n += !blank && !inWord;
        inWord = !blank;
    }
    return n;
}

/// Adds what a line starting at `p` with b, c, d or p creates: a box, cylinder, cone, disk or
/// plane, or a polygon's triangles.
void countShapeLine(const char* p, const char* end, Counts& c) {
    auto starts = [&](char a, char b, char d) { return p[0] == a && p[1] == b && p[2] == d; };
    if (starts('b', 'o', 'x') || starts('c', 'y', 'l') || starts('c', 'o', 'n') ||
        starts('d', 'i', 's') || starts('p', 'l', 'a'))
        ++c.shapes;
    if (starts('p', 'o', 'l')) {  // polygon: n vertices make n - 2 triangles
        size_t words = wordsOnLine(p, end);
        size_t tris = words >= 4 ? words - 3 : 0;
        c.triangles += tris;
        c.polygonTriangles += tris;
    }
}

Counts countLines(std::string_view text) {
    Counts c;
    const char* p = text.data();
    const char* end = p + text.size();
    while (p < end) {
        while (p < end && (*p == ' ' || *p == '\t')) ++p;
        if (end - p >= 3 && p[0] == 't' && p[1] == 'r' && p[2] == 'i') ++c.triangles;
        if (end - p >= 6 && p[0] == 's' && p[1] == 'p' && p[2] == 'h') ++c.spheres;
        if (end - p >= 6 && p[0] == 'v' && p[1] == 'e' && p[2] == 'r') ++c.vertices;
        if (end - p >= 3 && (static_cast<unsigned char>(p[0] - 'b') <= 'd' - 'b' || p[0] == 'p'))
            countShapeLine(p, end, c);
        const void* nl = std::memchr(p, '\n', static_cast<size_t>(end - p));
        p = nl ? static_cast<const char*>(nl) + 1 : end;
    }
    return c;
}

std::unique_ptr<Scene> Parser::run() {
    Counts counts = countLines(text_);
    size_t needed = Scene::estimateBytes(counts.triangles, counts.spheres, counts.shapes,
                                         counts.polygonTriangles) +
                    counts.vertices * (sizeof(Vec3) + sizeof(std::array<Vec3, 2>));
    size_t available = limits_.memoryBytes ? limits_.memoryBytes : availableMemoryBytes();
    if (available > 0 && needed > available)
        throw SceneError({file_, 0, 0},
                         "the scene needs about " + formatBytes(static_cast<double>(needed)) +
                             " of memory (" + std::to_string(counts.triangles) + " triangles, " +
                             std::to_string(counts.spheres) + " spheres" +
                             (counts.shapes ? ", " + std::to_string(counts.shapes) + " other shapes"
                                            : std::string()) +
                             "), more than the " + formatBytes(static_cast<double>(available)) +
                             " available");
    scene_->primitives.reserve(counts.triangles, counts.spheres, counts.shapes);
    vertices_.reserve(counts.vertices);
    size_t pos = text_.starts_with("\xEF\xBB\xBF") ? 3 : 0;  // a UTF-8 byte-order mark
    while (pos < text_.size()) {
        size_t end = text_.find('\n', pos);
        if (end == std::string_view::npos) end = text_.size();
        ++line_;
        tokenize(text_.substr(pos, end - pos));
        pos = end + 1;
        if (ntok_ == 0) continue;

        const Command* cmd = nullptr;
        for (const Command& c : commands())
            if (c.name == tok_[0].text) {
                cmd = &c;
                break;
            }
        if (!cmd) unknownCommand();
        int args = ntok_ - 1;
        if (args < cmd->minArgs || args > cmd->maxArgs) {
            // "1 or 2" for filter and lens, "3 or 6" for background, "3 to 1024" for polygon.
            bool twoCounts = cmd->name == "background" || cmd->maxArgs == cmd->minArgs + 1;
            std::string expect = cmd->minArgs == cmd->maxArgs
                                     ? std::to_string(cmd->minArgs)
                                     : std::to_string(cmd->minArgs) + (twoCounts ? " or " : " to ") +
                                           std::to_string(cmd->maxArgs);
            std::string msg = std::string(cmd->name) + " expects " + expect +
                              (cmd->maxArgs == 1 ? " argument" : " arguments");
            if (!cmd->usage.empty()) msg += " (" + std::string(cmd->usage) + ")";
            msg += ", got " + std::to_string(args);
            // Too many: point at the first extra argument; too few: at the command.
            fail(args > cmd->maxArgs ? std::min(cmd->maxArgs + 1, kMaxTokens - 1) : 0, msg);
        }
        if (cmd->name == "background" && args != 3 && args != 6)
            fail(4, "background expects 3 or 6 arguments (r g b [r2 g2 b2]), got " +
                        std::to_string(args));
        (this->*cmd->handler)();
    }
    if (!scene_->camera) {
        // Point just past the last line, where the missing command would go.
        throw SceneError({file_, line_ + 1, 1},
                         "the scene has no camera (add 'camera fromx fromy fromz atx aty atz "
                         "upx upy upz fovy')");
    }
    scene_->camera->apertureRadius = apertureRadius_;
    scene_->camera->focusDistance = focusDistance_;
    return std::move(scene_);
}

void Parser::tokenize(std::string_view line) {
    ntok_ = 0;
    auto isSpace = [](char c) {
        return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
    };
    size_t i = 0, n = line.size();
    while (i < n) {
        while (i < n && isSpace(line[i])) ++i;
        if (i >= n || line[i] == '#') break;  // end of line or a comment to the end
        size_t start = i;
        while (i < n && !isSpace(line[i])) ++i;
        if (ntok_ < kMaxTokens)
            tok_[ntok_] = {line.substr(start, i - start), static_cast<int>(start) + 1};
        ++ntok_;
    }
}

double Parser::number(int i) const {
    std::string_view s = tok_[i].text;
    const char* b = s.data();
    const char* e = b + s.size();
    double v = 0;
    if (parseDecimalFast(b, e, v)) return v;
    if (b != e && *b == '+' && e - b > 1 && b[1] != '-' && b[1] != '+') ++b;  // "+1"
    auto [p, ec] = std::from_chars(b, e, v);
    if (ec == std::errc::result_out_of_range && p == e) {
        // Overflow is an error; underflow (1e-400) reads as the nearest double, zero or tiny.
        v = std::strtod(std::string(b, e).c_str(), nullptr);
        if (std::isinf(v)) fail(i, "number " + quoted(i) + " is out of range");
        return v;
    }
    if (ec != std::errc() || p != e) fail(i, "expected a number, got " + quoted(i));
    if (!std::isfinite(v)) fail(i, "expected a finite number, got " + quoted(i));
    return v;
}

double Parser::real(int i) const {
    // Geometry is stored in float: larger magnitudes would become infinite there.
    double v = number(i);
    if (std::abs(v) > static_cast<double>(std::numeric_limits<float>::max()))
        fail(i, "number " + quoted(i) + " is too large");
    return v;
}

long long Parser::integer(int i, long long lo, long long hi) const {
    std::string_view s = tok_[i].text;
    const char* b = s.data();
    const char* e = b + s.size();
    long long v = 0;
    if (parseUnsignedFast(b, e, v) && v >= lo && v <= hi) return v;
    if (b != e && *b == '+' && e - b > 1 && b[1] != '-' && b[1] != '+') ++b;
    auto [p, ec] = std::from_chars(b, e, v);
    if (ec == std::errc::result_out_of_range || (ec == std::errc() && p == e && (v < lo || v > hi)))
        fail(i, "integer " + quoted(i) + " is out of range (" + std::to_string(lo) + " to " +
                    std::to_string(hi) + ")");
    if (ec != std::errc() || p != e) fail(i, "expected an integer, got " + quoted(i));
    return v;
}

const Transform& Parser::bakeTransform() {
    if (!transformValid_) {
        transform_ = Transform::fromMatrix(stack_.back());
        transformValid_ = true;
    }
    if (!transform_) fail(0, "the current transform is singular or not finite");
    return *transform_;
}

uint32_t Parser::vertexIndex(int i, size_t count, const char* one, const char* many) const {
    long long v = integer(i, 0, std::numeric_limits<uint32_t>::max());
    if (static_cast<size_t>(v) >= count) {
        if (count == 0)
            fail(i, "vertex index " + quoted(i) + " is out of range: no " + one +
                        " has been defined yet");
        fail(i, "vertex index " + quoted(i) + " is out of range: " + std::to_string(count) + " " +
                    (count == 1 ? std::string(one) + " is" : std::string(many) + " are") +
                    " defined (0 to " + std::to_string(count - 1) + ")");
    }
    return static_cast<uint32_t>(v);
}

void Parser::unknownCommand() {
    auto lower = [](std::string_view s) {
        std::string r(s);
        for (char& c : r) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
        return r;
    };
    // Edit distance, ignoring case, to the closest known command.
    auto distance = [](const std::string& a, const std::string& b) {
        std::vector<size_t> row(b.size() + 1);
        for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
        for (size_t i = 1; i <= a.size(); ++i) {
            size_t diag = row[0];
            row[0] = i;
            for (size_t j = 1; j <= b.size(); ++j) {
                size_t next = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] != b[j - 1])});
                diag = row[j];
                row[j] = next;
            }
        }
        return row[b.size()];
    };
    std::string word = lower(tok_[0].text);
    std::string_view best;
    size_t bestDistance = 3;  // suggest only near misses
    for (const Command& c : commands()) {
        size_t d = distance(word, lower(c.name));
        if (d < bestDistance) {
            bestDistance = d;
            best = c.name;
        }
    }
    std::string msg = "unknown command " + quoted(0);
    if (!best.empty()) msg += "; did you mean '" + std::string(best) + "'?";
    fail(0, msg);
}

void Parser::cmdSize() {
    long long w = integer(1, 1, kMaxImageSide);
    long long h = integer(2, 1, kMaxImageSide);
    if (w * h > kMaxImagePixels)
        fail(2, "image of " + std::to_string(w) + " x " + std::to_string(h) +
                    " pixels is too large (at most " + std::to_string(kMaxImagePixels) +
                    " pixels)");
    scene_->width = static_cast<int>(w);
    scene_->height = static_cast<int>(h);
}

void Parser::cmdMaxDepth() {
    long long d = integer(1, 0, std::numeric_limits<long long>::max());
    if (d > kMaxDepthLimit) {
        warn(1, "maxdepth " + std::to_string(d) + " is more than Glint traces; using " +
                    std::to_string(kMaxDepthLimit));
        d = kMaxDepthLimit;
    }
    scene_->maxDepth = static_cast<int>(d);
}

void Parser::cmdOutput() {
    scene_->output = std::string(tok_[1].text);
    if (!imageFormatFor(scene_->output))
        warn(1, "Glint cannot write " + quoted(1) +
                    ": use a .png, .ppm or .pfm name here or choose one with -o");
}

void Parser::cmdCamera() {
    CameraSpec c{vec3(1), vec3(4), vec3(7), real(10)};
    if (c.eye == c.center) fail(4, "the camera looks at its own position (from equals at)");
    if (!(length(c.eye - c.center) > 0) || !std::isfinite(length(c.eye - c.center)))
        fail(4, "the camera's viewing direction cannot be normalised");
    if (!(length(cross(c.up, normalize(c.eye - c.center))) > 0))
        fail(7, "the camera's up vector is zero or parallel to the viewing direction");
    if (!(c.fovyDegrees > 0 && c.fovyDegrees < 180))
        fail(10, "fovy must be between 0 and 180 degrees, got " + quoted(10));
    if (scene_->camera)
        warn(0, "a second camera replaces the one on line " + std::to_string(cameraLine_));
    scene_->camera = c;
    cameraLine_ = line_;
}

void Parser::cmdSphere() {
    Sphere s{vec3(1), real(4), {}};
    if (s.radius < 0) fail(4, "sphere radius must not be negative, got " + quoted(4));
    s.worldFromObject = transform();
    if (s.radius == 0) {
        warn(4, "sphere of radius 0 is invisible and is skipped");
        return;
    }
    Bounds3f b = s.bounds();
    if (!inRange(Vec3(b.lo)) || !inRange(Vec3(b.hi)))
        fail(0, "the sphere reaches beyond the supported coordinate range (1e18)");
    if (!(sphereSearch(s).largestEntry() <= kMaxCoordinate))
        fail(0, "the sphere is too thin: a semi-axis is below 1e-18 after the transform");
    scene_->primitives.addSphere(s, material());
}

void Parser::cmdMaxVerts() {
    maxVerts_ = integer(1, 0, std::numeric_limits<long long>::max());
    vertices_.reserve(static_cast<size_t>(std::min(maxVerts_, kMaxVertexReserve)));
}

void Parser::cmdMaxVertNorms() {
    maxVertNorms_ = integer(1, 0, std::numeric_limits<long long>::max());
    normalVertices_.reserve(static_cast<size_t>(std::min(maxVertNorms_, kMaxVertexReserve)));
}

void Parser::cmdVertex() {
    vertices_.push_back(vec3(1));
    if (maxVerts_ >= 0 && static_cast<long long>(vertices_.size()) > maxVerts_ && !warnedVerts_) {
        warn(0, "more vertices than 'maxverts " + std::to_string(maxVerts_) + "' announced");
        warnedVerts_ = true;
    }
}

void Parser::cmdVertexNormal() {
    Vec3 p = vec3(1), n = vec3(4);
    double len = length(n);
    if (!(len > 0) || !std::isfinite(len)) {
        warn(4,
             "vertex normal has zero length: it adds nothing to interpolated normals (where "
             "nothing remains, the face normal is used)");
        n = Vec3(0);
    } else {
        n = n / len;
    }
    normalVertices_.push_back({p, n});
    if (maxVertNorms_ >= 0 && static_cast<long long>(normalVertices_.size()) > maxVertNorms_ &&
        !warnedVertNorms_) {
        warn(0, "more vertices with normals than 'maxvertnorms " + std::to_string(maxVertNorms_) +
                    "' announced");
        warnedVertNorms_ = true;
    }
}

void Parser::cmdTri() {
    uint32_t i[3];
    for (int k = 0; k < 3; ++k) i[k] = vertexIndex(k + 1, vertices_.size(), "vertex", "vertices");
    const Transform& t = transform();
    Vec3 p[3];
    for (int k = 0; k < 3; ++k) p[k] = checkedVertex(t.point(vertices_[i[k]]), k + 1);
    addTriangle(p, nullptr);
}

void Parser::cmdTriNormal() {
    uint32_t i[3];
    for (int k = 0; k < 3; ++k)
        i[k] = vertexIndex(k + 1, normalVertices_.size(), "vertexnormal", "vertexnormals");
    const Transform& t = transform();
    Vec3 p[3], n[3];
    for (int k = 0; k < 3; ++k) {
        p[k] = checkedVertex(t.point(normalVertices_[i[k]][0]), k + 1);
        n[k] = t.normal(normalVertices_[i[k]][1]);
        double len = length(n[k]);
        n[k] = len > 0 && std::isfinite(len) ? n[k] / len : Vec3(0);
    }
    addTriangle(p, n);
}

void Parser::cmdTranslate() {
    Vec3 v = vec3(1);
    applyTransform(Mat4::translate(v.x, v.y, v.z));
}

void Parser::cmdRotate() {
    Vec3 axis = vec3(1);
    double degrees = number(4);
    if (axis == Vec3(0)) fail(1, "rotation axis must not be zero");
    applyTransform(Mat4::rotate(axis.x, axis.y, axis.z, degrees));
}

void Parser::cmdScale() {
    Vec3 s = vec3(1);
    for (int k = 0; k < 3; ++k)
        if (s[k] == 0) fail(k + 1, "scale by zero would make the transform singular");
    applyTransform(Mat4::scale(s.x, s.y, s.z));
}

void Parser::cmdPushTransform() { stack_.push_back(stack_.back()); }

void Parser::cmdPopTransform() {
    if (stack_.size() == 1) fail(0, "popTransform without a matching pushTransform");
    stack_.pop_back();
    transformValid_ = false;
}

void Parser::cmdDirectional() {
    Light l;
    l.kind = Light::Kind::Directional;
    Vec3 d = transform().vector(vec3(1));
    double len = length(d);
    if (!(len > 0) || !std::isfinite(len)) fail(1, "light direction must not be zero");
    l.direction = d / len;
    l.color = colour(4);
    scene_->lights.push_back(l);
}

void Parser::cmdPoint() {
    Light l;
    l.kind = Light::Kind::Point;
    l.position = transform().point(vec3(1));
    l.color = colour(4);
    l.attenuation = attenuation_;
    scene_->lights.push_back(l);
}

void Parser::cmdAttenuation() {
    Vec3 a = vec3(1);
    for (int k = 0; k < 3; ++k)
        if (a[k] < 0) fail(k + 1, "attenuation coefficients must not be negative");
    if (a == Vec3(0)) fail(1, "attenuation coefficients must not all be zero");
    attenuation_ = a;
}

void Parser::cmdShininess() {
    double s = real(1);
    if (s < 0) fail(1, "shininess must not be negative, got " + quoted(1));
    material_.shininess = s;
    materialChanged_ = true;
}

void Parser::cmdBackground() {
    scene_->background.down = colour(1);
    scene_->background.up = ntok_ == 7 ? colour(4) : scene_->background.down;
}

void Parser::cmdIor() {
    double n = real(1);
    if (!(n > 0)) fail(1, "ior must be positive, got " + quoted(1));
    material_.ior = n;
    materialChanged_ = true;
}

void Parser::cmdRoughness() {
    double a = real(1);
    if (!(a >= 0 && a <= 1)) fail(1, "roughness must be between 0 and 1, got " + quoted(1));
    // Below this the GGX lobe is a mirror in all but round-off: treat it as one.
    material_.roughness = a < 1e-4 ? 0 : a;
    materialChanged_ = true;
}

void Parser::cmdQuadLight() {
    const Transform& t = transform();
    Light l;
    l.kind = Light::Kind::Quad;
    l.position = checkedVertex(t.point(vec3(1)), 1);
    l.edge1 = t.vector(vec3(4));
    l.edge2 = t.vector(vec3(7));
    l.color = colour(10);
    Vec3 corners[4] = {l.position, l.position + l.edge1, l.position + l.edge1 + l.edge2,
                       l.position + l.edge2};
    for (int k = 1; k < 4; ++k)
        if (!inRange(corners[k]))
            fail(4, "the light reaches beyond the supported coordinate range (1e18)");
    double area = l.quadArea();
    if (!(area > 0) || !std::isfinite(area) ||
        !(area > 1e-12 * length(l.edge1) * length(l.edge2)))
        fail(4, "quadLight edges must not be zero or parallel");
    scene_->lights.push_back(l);
    // Its surface, visible to camera and reflected rays: emission only, from the front.
    Material m;
    m.ambient = Vec3(0);
    m.emission = l.color;
    m.frontEmissionOnly = true;
    uint32_t id = scene_->addMaterial(m);
    scene_->primitives.addTriangle(corners[0], corners[1], corners[2], nullptr, id);
    scene_->primitives.addTriangle(corners[0], corners[2], corners[3], nullptr, id);
    materialChanged_ = true;  // the current material must be added again after this one
}

void Parser::cmdFilter() {
    FilterSpec f;
    if (tok_[1].text == "box")
        f.kind = FilterSpec::Kind::Box;
    else if (tok_[1].text == "gaussian")
        f.kind = FilterSpec::Kind::Gaussian;
    else
        fail(1, "unknown filter " + quoted(1) + " (box or gaussian)");
    f.radius = FilterSpec::defaultRadius(f.kind);
    if (ntok_ == 3) {
        f.radius = real(2);
        if (!(f.radius >= 0.5 && f.radius <= 4))
            fail(2, "filter radius must be 0.5 to 4 pixels, got " + quoted(2));
    }
    scene_->filter = f;
}

void Parser::cmdLens() {
    double r = real(1);
    if (!(r >= 0)) fail(1, "aperture radius must not be negative, got " + quoted(1));
    double d = ntok_ == 3 ? real(2) : 0;
    if (ntok_ == 3 && !(d > 0)) fail(2, "focus distance must be positive, got " + quoted(2));
    apertureRadius_ = r;
    focusDistance_ = d;
}

// ---- Shape extensions ---------------------------------------------------------------------

void Parser::addShape(ShapeKind kind, const Mat4& objectFromCanonical, double k, const char* name) {
    const Transform& current = transform();  // a singular current transform is reported first
    std::optional<Transform> t = Transform::fromMatrix(current.matrix() * objectFromCanonical);
    const std::string the = std::string("the ") + name;
    if (!t) fail(0, the + " is degenerate after the transform (too thin or too large)");
    Shape shape{kind, k, *t};
    Bounds3f b = shape.bounds();
    if (!inRange(Vec3(b.lo)) || !inRange(Vec3(b.hi)))
        fail(0, the + " reaches beyond the supported coordinate range (1e18)");
    if (!(shape.search().largestEntry() <= kMaxCoordinate))
        fail(0, the + " is too thin: a dimension is below 1e-18 after the transform");
    scene_->primitives.addShape(shape, material());
}

void Parser::cmdPlane() {
    Vec3 point = vec3(1), normal = vec3(4);
    if (normal == Vec3(0)) fail(4, "plane normal must not be zero");
    const Transform& t = transform();
    if (!inRange(t.point(point)))
        fail(1,
             "the plane's point lies beyond the supported coordinate range (1e18) after the "
             "transform");
    std::optional<Plane> plane = Plane::make(point, normal, t);
    if (!plane) fail(4, "the plane's normal cannot be normalised after the transform");
    scene_->primitives.addPlane(*plane, material());
}

void Parser::cmdBox() {
    Vec3 a = vec3(1), b = vec3(4);
    for (int k = 0; k < 3; ++k)
        if (a[k] == b[k])
            fail(4 + k, std::string("box has zero extent along ") + "xyz"[k] +
                            ": both corners have " + "xyz"[k] + " = " + quoted(4 + k));
    addShape(ShapeKind::Box, boxPlacement(a, b), 1, "box");
}

void Parser::cmdCylinder() {
    Vec3 a = vec3(1), b = vec3(4);
    double r = real(7);
    if (a == b) fail(4, "the cylinder's end points coincide: its axis has no direction");
    if (!(r > 0)) fail(7, "cylinder radius must be positive, got " + quoted(7));
    addShape(ShapeKind::Cylinder, cylinderPlacement(a, b, r), 1, "cylinder");
}

void Parser::cmdCone() {
    Vec3 a = vec3(1), b = vec3(5);
    double r0 = real(4), r1 = real(8);
    if (r0 < 0) fail(4, "cone radius must not be negative, got " + quoted(4));
    if (r1 < 0) fail(8, "cone radius must not be negative, got " + quoted(8));
    if (r0 == 0 && r1 == 0) fail(4, "cone radii must not both be zero");
    if (a == b) fail(5, "the cone's end points coincide: its axis has no direction");
    double k = 1;
    Mat4 placement = conePlacement(a, r0, b, r1, k);
    addShape(ShapeKind::Cone, placement, k, "cone");
}

void Parser::cmdDisk() {
    Vec3 c = vec3(1), n = vec3(4);
    double r = real(7);
    if (n == Vec3(0)) fail(4, "disk normal must not be zero");
    if (!(r > 0)) fail(7, "disk radius must be positive, got " + quoted(7));
    addShape(ShapeKind::Disk, diskPlacement(c, n, r), 1, "disk");
}

void Parser::cmdPolygon() {
    const int n = ntok_ - 1;
    std::vector<uint32_t> index(static_cast<size_t>(n));
    std::vector<Vec3> points(static_cast<size_t>(n));
    for (int k = 0; k < n; ++k) {
        uint32_t v = vertexIndex(k + 1, vertices_.size(), "vertex", "vertices");
        for (int j = 0; j < k; ++j)
            if (index[static_cast<size_t>(j)] == v)
                fail(k + 1, "vertex index " + quoted(k + 1) + " appears twice in the polygon");
        index[static_cast<size_t>(k)] = v;
        points[static_cast<size_t>(k)] = vertices_[v];
    }
    PolygonTriangulation poly = triangulatePolygon(points);
    using Problem = PolygonTriangulation::Problem;
    const int at = poly.vertex + 1;  // the token of the vertex at fault
    auto edge = [&](int from) { return quoted(from + 1) + " to " + quoted((from + 1) % n + 1); };
    switch (poly.problem) {
        case Problem::None:
            break;
        case Problem::SamePosition:
            fail(at, "polygon vertex " + quoted(at) + " is at the same position as vertex " +
                         quoted(poly.other + 1));
        case Problem::ZeroArea:
            fail(0, "the polygon has zero area: its vertices lie on one line");
        case Problem::NonPlanar: {
            char off[32];
            std::snprintf(off, sizeof off, "%.2g%%", 100 * poly.offPlane);
            fail(at, "the polygon is not planar: vertex " + quoted(at) + " lies off its plane by " +
                         off + " of its size (at most 0.1% is allowed)");
        }
        case Problem::SelfIntersecting:
            fail(at, "the polygon's edges cross: the edge from vertex " + edge(poly.vertex) +
                         " meets the edge from vertex " + edge(poly.other));
    }
    const Transform& t = transform();
    std::vector<Vec3> world(static_cast<size_t>(n));
    for (int k = 0; k < n; ++k)
        world[static_cast<size_t>(k)] =
            checkedVertex(t.point(points[static_cast<size_t>(k)]), k + 1);
    // The polygon's normal shades all its triangles. Under a mirroring transform the vertex
    // order turns the other way, and the normal with it, as for `tri`.
    Mat4 m = t.matrix();
    double det = m.m[0][0] * (m.m[1][1] * m.m[2][2] - m.m[1][2] * m.m[2][1]) -
                 m.m[0][1] * (m.m[1][0] * m.m[2][2] - m.m[1][2] * m.m[2][0]) +
                 m.m[0][2] * (m.m[1][0] * m.m[2][1] - m.m[1][1] * m.m[2][0]);
    Vec3 normal = t.normal(poly.normal);
    normal = normal / maxComponent(abs(normal));  // no overflow or underflow in the length
    normal = normalize(normal) * (det < 0 ? -1.0 : 1.0);
    const Vec3 normals[3] = {normal, normal, normal};
    for (const auto& tri : poly.triangles) {
        Vec3 p[3] = {world[tri[0]], world[tri[1]], world[tri[2]]};
        addTriangle(p, isFinite(normal) ? normals : nullptr);
    }
}

}  // namespace

std::unique_ptr<Scene> parseHw3Scene(std::string_view text, const std::string& fileName,
                                     std::vector<Diagnostic>& warnings, const LoadLimits& limits) {
    return Parser(text, fileName, warnings, limits).run();
}

std::unique_ptr<Scene> loadHw3Scene(const std::string& path, std::vector<Diagnostic>& warnings,
                                    const LoadLimits& limits) {
    auto cannot = [&](const std::string& why) {
        throw SceneError({path, 0, 0}, "cannot read scene: " + why);
    };
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0) cannot(std::strerror(errno));
    if (S_ISDIR(st.st_mode)) cannot("it is a directory");
    if (!S_ISREG(st.st_mode)) cannot("not a regular file");
    if (st.st_size > kMaxSceneFileBytes)
        cannot("the file has " + std::to_string(st.st_size) + " bytes, more than the limit of " +
               std::to_string(kMaxSceneFileBytes));
    try {
        MappedFile file(path);
        return parseHw3Scene(file.text(), path, warnings, limits);
    } catch (const std::system_error& e) {
        throw SceneError({path, 0, 0},
                         std::string("cannot read scene: ") + std::strerror(e.code().value()));
    }
}

std::vector<std::string_view> hw3CommandNames() {
    std::vector<std::string_view> names;
    for (const Command& c : Parser::commands()) names.push_back(c.name);
    return names;
}

}  // namespace glint
