#pragma once
// The parser of the CSE167x scene format, shared by the files that implement it:
// course_loader.cpp (reading, lexing, arguments, diagnostics, the command table),
// course_commands.cpp (the course's commands), course_extensions.cpp (Glint's extensions) and
// course_meshes.cpp (meshes and textures). Internal to io/course: use course_loader.h.

#include <array>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "glint/core/error.h"
#include "glint/geometry/shape_search.h"
#include "glint/io/course/course_loader.h"
#include "glint/math/mat4.h"
#include "glint/scene/mesh.h"
#include "glint/scene/model.h"
#include "glint/scene/scene.h"
#include "glint/scene/scene_builder.h"

namespace glint::course {

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
           const CourseOptions& options)
        : text_(text),
          file_(file),
          warnings_(warnings),
          limits_(options.limits),
          lenient_(options.lenient),
          time_(options.time),
          assets_(options.assets),
          models_(options.models) {}

    std::unique_ptr<Scene> run();
    static const std::vector<Command>& commands();

  private:
    /// Reads the lines from `pos` on, each command in turn.
    void readLines(size_t pos);

    // Lexing and diagnostics.
    void tokenize(std::string_view line);
    FileLoc loc(int column) const { return {file_, line_, column}; }
    [[noreturn]] void fail(int token, const std::string& message) const {
        throw SceneError(loc(tok_[token].column), message);
    }
    void warn(int token, const std::string& message) {
        warnings_.push_back({loc(tok_[token].column), message});
    }
    /// Warns at the command of a problem that may recur, once per `key`: the warning, at its
    /// first occurrence, reads `head`, then "(N times; first here)" once it recurs, then
    /// `tail`.
    void warnRepeated(const std::string& key, const std::string& head, const std::string& tail);
    /// Where the first command is, or line 0 if the text has none.
    FileLoc firstCommand();
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
    /// Argument `i` (or three from it), each between 0 and 1, named `what` in errors.
    double unitArgument(int i, const char* what) const;
    Vec3 unitColour(int i, const char* what) const;
    /// The builder's current transform; a singular one is a BuildError, which run() reports at
    /// the command.
    const Transform& transform() { return builder_.transform(); }
    /// Argument `i` as an index into a pile of `count` entries, named `one` / `many`.
    uint32_t vertexIndex(int i, size_t count, const char* one, const char* many) const;
    /// `p`, a transformed vertex named by argument `i`, if it is within the coordinate range.
    Vec3 checkedVertex(const Vec3& p, int i) const {
        if (!withinCoordinateRange(p))
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
    void cmdPushTransform() {
        builder_.pushTransform();
        motion_.push_back(motion_.back());
    }
    void cmdMotion();
    void cmdPopTransform();
    void cmdDirectional();
    void cmdPoint();
    void cmdSpot();
    void cmdAttenuation();
    void cmdAmbient() { builder_.editMaterial().ambient = colour(1); }
    void cmdDiffuse() { builder_.editMaterial().diffuse = colour(1); }
    void cmdSpecular() { builder_.editMaterial().specular = colour(1); }
    void cmdEmission() { builder_.editMaterial().emission = colour(1); }
    void cmdShininess();
    void cmdBackground();
    // Extensions beyond Whitted (docs/scene-format.md).
    void cmdTransmission() { builder_.editMaterial().transmission = colour(1); }
    void cmdIor();
    void cmdRoughness();
    void cmdQuadLight();
    void cmdLightSamples() { scene().lightSamples = static_cast<int>(integer(1, 1, 64)); }
    void cmdSpp() { scene().spp = static_cast<int>(integer(1, 1, 65536)); }
    void cmdFilter();
    void cmdLens();
    void cmdIntegrator();
    void cmdEnvironment();
    // The shape extensions (docs/scene-format.md).
    void cmdPlane();
    void cmdBox();
    void cmdCylinder();
    void cmdCone();
    void cmdDisk();
    void cmdPolygon();
    // Meshes and textures (docs/scene-format.md, "Meshes" and "Textures").
    void cmdMesh();
    void cmdTexture();
    void cmdMetallic();
    void cmdClearcoat();
    void cmdSheen();
    void cmdSpecularFactor();
    void cmdAnisotropy();
    void cmdIridescence();
    void cmdDiffuseTransmission();
    void cmdMedium();
    void cmdInterior();
    void cmdFog();
    /// The medium argument `token` names (`none`: 0).
    uint32_t mediumNamed(int token) const;
    /// `texture SLOT file [wrap]` and `texture SLOT none`: a physically based map.
    void cmdTextureMap();
    /// The image at scene-relative `name` (token 1 or 2), read once per scene.
    std::shared_ptr<const TextureImage> sceneImage(int token, bool srgb);
    void cmdChecker();
    /// `name`, a file named in the scene, relative to the scene file's directory.
    std::string scenePath(std::string_view name) const;
    /// Warns once if surfaces without texture coordinates use an image texture.
    void checkTextureCoordinates(const Scene& scene);
    Scene& scene() { return builder_.scene(); }
    void addTriangle(const Vec3 (&p)[3], const Vec3* normals) {
        if (!builder_.addTriangle(p, normals) && !warnedDegenerate_) {
            warn(0, "triangle has zero area and is skipped (later ones are skipped silently)");
            warnedDegenerate_ = true;
        }
    }
    /// Fails at an unknown command, or when lenient warns and returns.
    void unknownCommand();

    std::string_view text_;
    const std::string& file_;
    std::vector<Diagnostic>& warnings_;
    LoadLimits limits_;
    bool lenient_;
    ModelTime time_;            ///< The scene's time and shutter (`motion`, `mesh`).
    class AssetCache* assets_;  ///< Where `mesh` files are kept; may be null.
    /// `motion`: what moves what follows it, until its transform is popped.
    struct Motion {
        Mat4 frame;     ///< The transform when it was given: the motion acts inside it.
        Vec3 velocity;  ///< Per second.
        Vec3 axis{0, 1, 0};
        double degreesPerSecond = 0;
    };
    std::vector<std::optional<Motion>> motion_{std::nullopt};  ///< By transform stack level.
    bool warnedStillTriangles_ = false;
    /// The current transform where the current motion puts it: at the scene's time (one
    /// matrix), or at the shutter's keys (several); empty without a motion.
    std::vector<Mat4> movedTransforms();
    /// Adds one sphere or shape by `add` (false: nothing added) where the current motion
    /// places it, moving over the shutter if there is one.
    void addMoving(const std::function<bool()>& add);
    /// Warns, once, that triangles given under a motion do not move.
    void noteStillTriangles();
    SceneBuilder builder_;

    int line_ = 0;
    std::array<Token, kMaxTokens> tok_;
    std::map<std::string, uint32_t, std::less<>> media_;  ///< Named media, by id.
    int ntok_ = 0;  ///< Tokens on the line, possibly more than kMaxTokens (only those are kept).

    LargeVector<Vec3> vertices_;
    std::vector<std::array<Vec3, 2>> normalVertices_;  ///< Position and unit normal (or zero).
    long long maxVerts_ = -1, maxVertNorms_ = -1;
    bool warnedVerts_ = false, warnedVertNorms_ = false, warnedDegenerate_ = false;
    int cameraLine_ = 0;
    int environmentLine_ = 0;  ///< Of the last `environment`, for the warning of a second one.
    int pointLights_ = 0, firstPointLine_ = 0;  ///< For the attenuation warning.
    bool warnedAttenuation_ = false;
    /// Warnings of problems that recur (warnRepeated), by key: the warning and its count.
    std::map<std::string, std::pair<size_t, int>> repeated_;
    /// Read by `mesh`, by path: each read once (and once a sequence, CourseOptions::assets).
    std::map<std::string, std::shared_ptr<const Model>> models_;
    std::map<std::string, std::shared_ptr<const TextureImage>> images_;  ///< By path.
    std::map<uint32_t, FileLoc> imageTextures_;  ///< Where each image texture was declared.
};

}  // namespace glint::course
