#include "glint/io/course/course_loader.h"

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

#include "glint/core/mapped_file.h"
#include "glint/core/parse_float.h"
#include "glint/core/system.h"
#include "glint/geometry/polygon.h"
#include "glint/io/course/course_parser.h"
#include "glint/io/course/numbers.h"
#include "glint/io/image/image_io.h"

namespace glint {
namespace course {

const std::vector<Command>& Parser::commands() {
    // The most frequent commands first: lookup is a linear scan.
    static const std::vector<Command> table = {
        {"vertex", 3, 3, "x y z", &Parser::cmdVertex},
        {"tri", 3, 3, "v1 v2 v3", &Parser::cmdTri},
        {"sphere", 4, 4, "x y z radius", &Parser::cmdSphere},
        {"pushTransform", 0, 0, "", &Parser::cmdPushTransform},
        {"popTransform", 0, 0, "", &Parser::cmdPopTransform},
        {"motion", 3, 7, "vx vy vz [ax ay az degrees]", &Parser::cmdMotion},
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
        {"spot", 11, 11, "x y z dx dy dz r g b inner outer", &Parser::cmdSpot},
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
        {"integrator", 1, 1, "name", &Parser::cmdIntegrator},
        {"environment", 1, 3, "file [scale] [rotation]", &Parser::cmdEnvironment},
        {"plane", 6, 6, "px py pz nx ny nz", &Parser::cmdPlane},
        {"box", 6, 6, "x0 y0 z0 x1 y1 z1", &Parser::cmdBox},
        {"cylinder", 7, 7, "x0 y0 z0 x1 y1 z1 radius", &Parser::cmdCylinder},
        {"cone", 8, 8, "x0 y0 z0 r0 x1 y1 z1 r1", &Parser::cmdCone},
        {"disk", 7, 7, "cx cy cz nx ny nz radius", &Parser::cmdDisk},
        {"polygon", 3, kMaxPolygonVertices, "v1 v2 v3 ...", &Parser::cmdPolygon},
        {"mesh", 1, 1, "file.obj", &Parser::cmdMesh},
        {"texture", 1, 3, "[slot] file [repeat|clamp|mirror], or [slot] none", &Parser::cmdTexture},
        {"metallic", 1, 1, "m", &Parser::cmdMetallic},
        {"clearcoat", 1, 2, "weight [roughness]", &Parser::cmdClearcoat},
        {"sheen", 3, 4, "r g b [roughness]", &Parser::cmdSheen},
        {"specularfactor", 1, 4, "factor [r g b]", &Parser::cmdSpecularFactor},
        {"anisotropy", 1, 2, "strength [rotation-degrees]", &Parser::cmdAnisotropy},
        {"iridescence", 1, 3, "factor [ior [thickness-nm]]", &Parser::cmdIridescence},
        {"diffusetransmission", 1, 4, "factor [r g b]", &Parser::cmdDiffuseTransmission},
        {"medium", 1, 24, "name [absorption r g b] [scattering r g b] [g value] ...",
         &Parser::cmdMedium},
        {"interior", 1, 2, "medium|none [interface]", &Parser::cmdInterior},
        {"fog", 1, 1, "medium|none", &Parser::cmdFog},
        {"checker", 7, 7, "r1 g1 b1 r2 g2 b2 scale", &Parser::cmdChecker},
    };
    return table;
}

namespace {

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

}  // namespace

std::unique_ptr<Scene> Parser::run() {
    Counts counts = countLines(text_);
    size_t needed = Scene::estimateBytes(counts.triangles, counts.spheres, counts.shapes,
                                         counts.polygonTriangles) +
                    counts.vertices * (sizeof(Vec3) + sizeof(std::array<Vec3, 2>));
    size_t available = memoryAvailable(limits_);
    if (available > 0 && needed > available)
        throw SceneError({file_, 0, 0},
                         "the scene needs about " + formatBytes(static_cast<double>(needed)) +
                             " of memory (" + std::to_string(counts.triangles) + " triangles, " +
                             std::to_string(counts.spheres) + " spheres" +
                             (counts.shapes ? ", " + std::to_string(counts.shapes) + " other shapes"
                                            : std::string()) +
                             "), more than the " + formatBytes(static_cast<double>(available)) +
                             " available");
    builder_.reserve(counts.triangles, counts.spheres, counts.shapes);
    vertices_.reserve(counts.vertices);
    size_t pos = text_.starts_with("\xEF\xBB\xBF") ? 3 : 0;  // a UTF-8 byte-order mark
    try {
        readLines(pos);
    } catch (const BuildError& e) {
        fail(0, e.what());  // what the builder refused, at the command that asked
    }
    if (!scene().camera) {
        // At the first command: the camera usually comes first.
        FileLoc first = firstCommand();
        if (first.line == 0) throw SceneError({file_, 0, 0}, "the scene file has no commands");
        throw SceneError(first,
                         "the scene has no camera (add 'camera fromx fromy fromz atx aty atz "
                         "upx upy upz fovy')");
    }
    std::unique_ptr<Scene> scene = builder_.finish(&warnings_);
    if (!imageTextures_.empty()) checkTextureCoordinates(*scene);
    return scene;
}

void Parser::readLines(size_t pos) {
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
        if (!cmd) {
            unknownCommand();
            continue;
        }
        int args = ntok_ - 1;
        if (args < cmd->minArgs || args > cmd->maxArgs) {
            // "1 or 2" for filter and lens, "3 or 6" for background, "3 to 1024" for polygon.
            bool twoCounts = cmd->name == "background" || cmd->maxArgs == cmd->minArgs + 1;
            std::string expect = cmd->minArgs == cmd->maxArgs ? std::to_string(cmd->minArgs)
                                                              : std::to_string(cmd->minArgs) +
                                                                    (twoCounts ? " or " : " to ") +
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
    auto [p, ec] = parseFloat(b, e, v);
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
    std::string suggestion = best.empty() ? "" : "; did you mean '" + std::string(best) + "'?";
    if (!lenient_)
        fail(0,
             "unknown command " + quoted(0) + " (--lenient skips unknown commands)" + suggestion);
    warnRepeated(std::string(tok_[0].text), "unknown command " + quoted(0) + " skipped",
                 suggestion);
}

void Parser::warnRepeated(const std::string& key, const std::string& head,
                          const std::string& tail) {
    auto [it, first] = repeated_.try_emplace(key, warnings_.size(), 1);
    if (first) {
        warn(0, head + tail);
        return;
    }
    auto& [index, count] = it->second;
    warnings_[index].message = head + " (" + std::to_string(++count) + " times; first here)" + tail;
}

FileLoc Parser::firstCommand() {
    line_ = 0;
    for (size_t pos = text_.starts_with("\xEF\xBB\xBF") ? 3 : 0; pos < text_.size();) {
        size_t end = std::min(text_.find('\n', pos), text_.size());
        ++line_;
        tokenize(text_.substr(pos, end - pos));
        if (ntok_ > 0) return loc(tok_[0].column);
        pos = end + 1;
    }
    return {file_, 0, 0};
}

}  // namespace course

using course::Command;
using course::Parser;

std::unique_ptr<Scene> parseCourseScene(std::string_view text, const std::string& fileName,
                                        std::vector<Diagnostic>& warnings,
                                        const CourseOptions& options) {
    return Parser(text, fileName, warnings, options).run();
}

std::unique_ptr<Scene> loadCourseScene(const std::string& path, std::vector<Diagnostic>& warnings,
                                       const CourseOptions& options) {
    if (std::string problem = inputFileProblem(path); !problem.empty())
        throw SceneError({path, 0, 0}, "cannot read scene: " + problem);
    try {
        MappedFile file(path);
        return parseCourseScene(file.text(), path, warnings, options);
    } catch (const std::system_error& e) {
        throw SceneError({path, 0, 0},
                         std::string("cannot read scene: ") + std::strerror(e.code().value()));
    }
}

std::vector<std::string_view> courseCommandNames() {
    std::vector<std::string_view> names;
    for (const Command& c : Parser::commands()) names.push_back(c.name);
    return names;
}

}  // namespace glint
