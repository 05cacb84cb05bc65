// glTF 2.0 assets: the default scene's node trees flattened into placements, the first
// perspective camera and the punctual lights, the meshes the placements use (after the memory
// they need is checked), and placing them. The container and tinygltf's parse are in
// gltf_container.cpp, meshes in gltf_meshes.cpp, materials in gltf_materials.cpp.

#include "glint/io/gltf/gltf_loader.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <numbers>
#include <optional>
#include <set>
#include <system_error>

#include "glint/core/mapped_file.h"
#include "glint/core/system.h"
#include "glint/io/gltf/gltf_internal.h"
#include "glint/scene/tangents.h"

namespace glint {
namespace gltf {

Context::Context(const std::string& file_, std::vector<Diagnostic>& warnings_,
                 const GltfOptions& options_)
    : file(file_),
      dir(std::filesystem::path(file_).parent_path().string()),
      warnings(warnings_),
      options(options_) {}

void Context::fail(const std::string& message) const { throw SceneError({file, 0, 0}, message); }

void Context::warn(const std::string& message) {
    Diagnostic d;  // built in steps: GCC 12 warns falsely on the aggregate
    d.loc.file = file;
    d.message = message;
    warnings.push_back(std::move(d));
}

void Context::warnOnce(const std::string& key, const std::string& message) {
    if (warned_.insert(key).second) warn(message + " (reported once)");
}

std::string describe(const char* kind, size_t index, const std::string& name) {
    std::string s = std::string(kind) + " " + std::to_string(index);
    if (!name.empty()) s += " '" + name + "'";
    return s;
}

void missing(const Context& ctx, const char* kind, long long index, size_t count,
             const std::string& user) {
    std::string plural = std::string(kind) + (std::string_view(kind).ends_with("h") ? "es" : "s");
    ctx.fail(std::string(kind) + " " + std::to_string(index) + " does not exist (the file has " +
             std::to_string(count) + " " + (count == 1 ? std::string(kind) : plural) +
             "): " + user + " refers to it");
}

std::string_view bufferViewBytes(const Context& ctx, int index, const std::string& user) {
    const auto& views = ctx.model.bufferViews;
    if (index < 0 || static_cast<size_t>(index) >= views.size())
        missing(ctx, "bufferView", index, views.size(), user);
    if (std::optional<std::string_view> decoded = meshoptBufferView(ctx, index)) return *decoded;
    const tinygltf::BufferView& bv = views[static_cast<size_t>(index)];
    const std::string label = "bufferView " + std::to_string(index);
    const auto& buffers = ctx.model.buffers;
    if (bv.buffer < 0 || static_cast<size_t>(bv.buffer) >= buffers.size())
        missing(ctx, "buffer", bv.buffer, buffers.size(), label);
    const std::vector<unsigned char>& data = buffers[static_cast<size_t>(bv.buffer)].data;
    if (bv.byteOffset > data.size() || bv.byteLength > data.size() - bv.byteOffset)
        ctx.fail(label + ": its " + std::to_string(bv.byteLength) + " bytes from offset " +
                 std::to_string(bv.byteOffset) + " lie beyond the end of buffer " +
                 std::to_string(bv.buffer) + " (" + std::to_string(data.size()) + " bytes)");
    return {reinterpret_cast<const char*>(data.data()) + bv.byteOffset, bv.byteLength};
}

namespace {

Vec3 applyPoint(const Mat4& m, const Vec3& p) {
    return {m.m[0][0] * p.x + m.m[0][1] * p.y + m.m[0][2] * p.z + m.m[0][3],
            m.m[1][0] * p.x + m.m[1][1] * p.y + m.m[1][2] * p.z + m.m[1][3],
            m.m[2][0] * p.x + m.m[2][1] * p.y + m.m[2][2] * p.z + m.m[2][3]};
}

Vec3 applyVector(const Mat4& m, const Vec3& v) {
    return {m.m[0][0] * v.x + m.m[0][1] * v.y + m.m[0][2] * v.z,
            m.m[1][0] * v.x + m.m[1][1] * v.y + m.m[1][2] * v.z,
            m.m[2][0] * v.x + m.m[2][1] * v.y + m.m[2][2] * v.z};
}

}  // namespace

Mat4 localMatrix(const Context& ctx, size_t node, const std::string& label) {
    const tinygltf::Node& n = ctx.model.nodes[node];
    const AnimatedNode* animated = node < ctx.animated.size() ? &ctx.animated[node] : nullptr;
    auto numbers = [&](const std::vector<double>& v, size_t count, const char* what) {
        if (v.empty()) return false;
        if (v.size() != count)
            ctx.fail(label + ": '" + what + "' must have " + std::to_string(count) +
                     " numbers, got " + std::to_string(v.size()));
        for (double x : v)
            if (!std::isfinite(x)) ctx.fail(label + ": '" + what + "' must be finite numbers");
        return true;
    };
    Mat4 m;
    // An animated node has no matrix (glTF 2.0, "Animations"); playAnimation refuses one.
    if (numbers(n.matrix, 16, "matrix")) {
        for (int c = 0; c < 4; ++c)  // glTF stores matrices column by column
            for (int r = 0; r < 4; ++r) m.m[r][c] = n.matrix[static_cast<size_t>(c * 4 + r)];
        if (m.m[3][0] != 0 || m.m[3][1] != 0 || m.m[3][2] != 0 || m.m[3][3] != 1)
            ctx.fail(label + ": its matrix is not affine (the last row must be 0 0 0 1)");
        return m;
    }
    double t[3] = {0, 0, 0}, q[4] = {0, 0, 0, 1}, s[3] = {1, 1, 1};
    if (numbers(n.translation, 3, "translation")) std::copy_n(n.translation.begin(), 3, t);
    if (numbers(n.scale, 3, "scale")) std::copy_n(n.scale.begin(), 3, s);
    if (numbers(n.rotation, 4, "rotation")) {
        double len = std::hypot(n.rotation[0], n.rotation[1], n.rotation[2]);
        len = std::hypot(len, n.rotation[3]);
        if (!(len > 0) || !std::isfinite(len))
            ctx.fail(label + ": its rotation must be a non-zero quaternion");
        for (int i = 0; i < 4; ++i) q[i] = n.rotation[static_cast<size_t>(i)] / len;
    }
    if (animated) {
        if (animated->translation) std::copy_n(animated->translation->begin(), 3, t);
        if (animated->scale) std::copy_n(animated->scale->begin(), 3, s);
        if (animated->rotation) std::copy_n(animated->rotation->begin(), 4, q);
    }
    const double x = q[0], y = q[1], z = q[2], w = q[3];
    const double r[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)},
                            {2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)},
                            {2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)}};
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) m.m[i][j] = r[i][j] * s[j];
        m.m[i][3] = t[i];
    }
    return m;
}

namespace {

/// A node with a camera, as the walk meets it.
struct CameraNode {
    int camera;               ///< Index into the file's cameras.
    size_t node;              ///< Index into its nodes.
    Mat4 world;               ///< The node's world transform.
    std::string description;  ///< "camera 0 'Main' (node 3)"
};

/// The camera of a camera node, if it is one Glint can use; else `problem` says why not.
std::optional<ModelCamera> nodeCamera(const Context& ctx, const CameraNode& node,
                                      std::string& problem) {
    const tinygltf::Camera& c = ctx.model.cameras[static_cast<size_t>(node.camera)];
    const Mat4& world = node.world;
    ModelCamera out;
    out.description = node.description;
    if (c.type != "perspective") {
        problem = out.description + " is " + c.type + ", and Glint has perspective cameras only";
        return std::nullopt;
    }
    const double yfov = c.perspective.yfov;
    if (!(yfov > 0 && yfov < std::numbers::pi))
        ctx.fail(out.description + ": yfov must be between 0 and pi radians");
    Vec3 eye = applyPoint(world, Vec3(0)), forward = applyVector(world, {0, 0, -1});
    Vec3 up = applyVector(world, {0, 1, 0});
    double fl = length(forward), ul = length(up);
    if (!isFinite(eye) || !withinCoordinateRange(eye) || !(fl > 0) || !std::isfinite(fl) ||
        !(ul > 0) || !std::isfinite(ul) || !(length(cross(forward / fl, up / ul)) > 1e-6)) {
        problem = out.description + ": its node's transform gives it no position or view direction";
        return std::nullopt;
    }
    out.spec.eye = eye;
    // A center as far away as the eye is from the origin, so that the view direction survives
    // the rounding of eye + direction.
    double reach = std::max({1.0, std::abs(eye.x), std::abs(eye.y), std::abs(eye.z)});
    out.spec.center = eye + forward * (reach / fl);
    out.spec.up = up / ul;
    out.spec.fovyDegrees = yfov * 180 / std::numbers::pi;
    const double aspect = c.perspective.aspectRatio;
    if (std::isfinite(aspect) && aspect > 0) out.aspectRatio = aspect;
    return out;
}

/// Light `index` of KHR_lights_punctual, placed by `world`, if Glint can use it.
std::optional<LightSpec> nodeLight(Context& ctx, int index, const Mat4& world,
                                   const std::string& node) {
    const tinygltf::Light& l = ctx.model.lights[static_cast<size_t>(index)];
    const std::string label = describe("light", static_cast<size_t>(index), l.name);
    Vec3 colour(1);
    if (!l.color.empty()) {
        if (l.color.size() != 3)
            ctx.fail(label + ": its color must have 3 numbers, got " +
                     std::to_string(l.color.size()));
        colour = {l.color[0], l.color[1], l.color[2]};
    }
    if (!isFinite(colour) || colour.x < 0 || colour.y < 0 || colour.z < 0 ||
        !std::isfinite(l.intensity) || l.intensity < 0)
        ctx.fail(label + ": its color and intensity must be finite numbers, not negative");
    LightSpec out;
    // Candela (point, spot) and lux (directional) as the path tracer's radiant intensity and
    // irradiance: a white matte surface lit head-on at 1 m shows intensity / pi, as Cycles
    // (the importer's 'COMPAT' lighting) and three.js show it. The classic look scales them
    // to the course's convention (model_framing.h).
    out.color = colour * l.intensity;
    if (l.type == "point" || l.type == "spot") {
        out.kind = LightSpec::Kind::Point;
        out.position = applyPoint(world, Vec3(0));
        out.attenuation = {0, 0, 1};
        // The spec's range; 0 or none: unlimited (a negative or non-finite one too).
        if (std::isfinite(l.range) && l.range > 0) out.range = l.range;
        if (l.type == "spot") {
            // It shines along its node's -z, fully within innerConeAngle, not at all beyond
            // outerConeAngle (the spec asks 0 <= inner < outer <= pi/2: others are brought
            // within that, with a warning).
            out.kind = LightSpec::Kind::Spot;
            const Vec3 along = applyVector(world, {0, 0, -1});
            const double len = length(along);
            if (!(len > 0) || !std::isfinite(len))
                out.position = Vec3(1e300);  // ignored below
            else
                out.axis = along / len;
            double inner = l.spot.innerConeAngle, outer = l.spot.outerConeAngle;
            constexpr double kRight = std::numbers::pi / 2;
            if (!std::isfinite(inner) || !std::isfinite(outer) || inner < 0 || outer <= 0 ||
                outer > kRight || inner >= outer) {
                char angles[64];
                std::snprintf(angles, sizeof angles, "inner %g, outer %g", inner, outer);
                ctx.warn(label + ": its cone angles (" + angles +
                         ") are not 0 <= inner < outer <= pi/2: taken within those bounds");
                outer = std::isfinite(outer) ? std::clamp(outer, 1e-4, kRight) : kRight / 2;
                inner = std::isfinite(inner) ? std::clamp(inner, 0.0, outer * 0.999) : 0;
            }
            out.cosInner = std::cos(inner);
            out.cosOuter = std::cos(outer);
        }
        if (isFinite(out.position) && withinCoordinateRange(out.position)) return out;
    } else if (l.type == "directional") {
        out.kind = LightSpec::Kind::Directional;
        Vec3 towards = applyVector(world, {0, 0, 1});  // it shines along its node's -z
        double len = length(towards);
        if (len > 0 && std::isfinite(len)) {
            out.direction = towards / len;
            return out;
        }
    } else {
        ctx.warn(label + ": light type '" + l.type + "' is unknown: it is ignored");
        return std::nullopt;
    }
    ctx.warn(label + " (" + node +
             "): its node's transform leaves it no position or direction: "
             "it is ignored");
    return std::nullopt;
}

/// "0 = camera 0 'Main' (node 3), 1 = camera 1 (node 5)": the cameras a choice may name.
std::string cameraList(const std::vector<CameraNode>& cameras) {
    if (cameras.empty()) return "the file has no cameras";
    std::string s = "the file has " + std::to_string(cameras.size()) +
                    (cameras.size() == 1 ? " camera: " : " cameras: ");
    constexpr size_t kListed = 20;
    for (size_t i = 0; i < cameras.size() && i < kListed; ++i)
        s += (i ? ", " : "") + std::to_string(i) + " = " + cameras[i].description;
    if (cameras.size() > kListed) s += ", ...";
    return s;
}

/// The camera `choice` (an Index or a Name) picks among the camera nodes met, in the order
/// met. (The first usable camera, the default, is chosen during the walk.)
std::optional<ModelCamera> chooseCamera(Context& ctx, const std::vector<CameraNode>& cameras,
                                        const CameraChoice& choice) {
    using Kind = CameraChoice::Kind;
    std::string problem;
    switch (choice.kind) {
        case Kind::None:
        case Kind::First:
        case Kind::Orbit:  // none of the file's (io/registry.cpp places it)
            return std::nullopt;
        case Kind::Index:
            if (choice.index >= cameras.size())
                ctx.fail("there is no camera " + std::to_string(choice.index) +
                         " (cameras are numbered from 0 in the order of the node tree): " +
                         cameraList(cameras));
            if (auto camera = nodeCamera(ctx, cameras[choice.index], problem)) return camera;
            ctx.fail("camera " + std::to_string(choice.index) + ": " + problem);
        case Kind::Name:
            for (const CameraNode& c : cameras) {
                const tinygltf::Camera& camera = ctx.model.cameras[static_cast<size_t>(c.camera)];
                if (camera.name != choice.name && ctx.model.nodes[c.node].name != choice.name)
                    continue;
                if (auto chosen = nodeCamera(ctx, c, problem)) return chosen;
                ctx.fail("camera '" + choice.name + "': " + problem);
            }
            ctx.fail("no camera or camera node is named '" + choice.name +
                     "': " + cameraList(cameras));
    }
    return std::nullopt;
}

/// Walks the default scene's node trees (or every root node when the file has no scene):
/// placements (those of skinned meshes into `skinned` as well), the camera
/// ctx.options.camera chooses and the lights.
void walkNodes(Context& ctx, Model& out, std::vector<SkinnedPlacement>& skinned) {
    const auto& nodes = ctx.model.nodes;
    const auto& scenes = ctx.model.scenes;
    std::vector<int> roots;
    std::string rootUser;
    if (!scenes.empty()) {
        int s = ctx.model.defaultScene == -1 ? 0 : ctx.model.defaultScene;
        if (s < 0 || static_cast<size_t>(s) >= scenes.size())
            missing(ctx, "scene", s, scenes.size(), "the default scene ('scene')");
        roots = scenes[static_cast<size_t>(s)].nodes;
        rootUser = "scene " + std::to_string(s);
    } else {
        std::vector<bool> isChild(nodes.size());
        for (size_t i = 0; i < nodes.size(); ++i)
            for (int c : nodes[i].children)
                if (c >= 0 && static_cast<size_t>(c) < nodes.size())
                    isChild[static_cast<size_t>(c)] = true;
        for (size_t i = 0; i < nodes.size(); ++i)
            if (!isChild[i]) roots.push_back(static_cast<int>(i));
        rootUser = "the file's root nodes";
    }

    struct Pending {
        int node;
        Mat4 parent;
        int from;  ///< The parent node, or -1 for a root.
    };
    std::vector<Pending> stack;
    for (auto it = roots.rbegin(); it != roots.rend(); ++it) stack.push_back({*it, Mat4(), -1});
    std::vector<bool> visited(nodes.size());
    std::vector<CameraNode> cameras;
    const bool firstCamera = ctx.options.camera.kind == CameraChoice::Kind::First;
    while (!stack.empty()) {
        Pending p = stack.back();
        stack.pop_back();
        if (p.node < 0 || static_cast<size_t>(p.node) >= nodes.size())
            missing(ctx, "node", p.node, nodes.size(),
                    p.from < 0 ? rootUser : "node " + std::to_string(p.from) + "'s children");
        const size_t index = static_cast<size_t>(p.node);
        const tinygltf::Node& n = nodes[index];
        const std::string label = describe("node", index, n.name);
        if (visited[index])
            ctx.fail(label +
                     " is reached twice: glTF nodes form trees (no node has two parents "
                     "or is its own ancestor)");
        visited[index] = true;
        const Mat4 world = p.parent * localMatrix(ctx, index, label);

        if (n.mesh != -1) {
            if (n.mesh < 0 || static_cast<size_t>(n.mesh) >= ctx.model.meshes.size())
                missing(ctx, "mesh", n.mesh, ctx.model.meshes.size(), label);
            if (n.skin != -1) {
                // The skin places the mesh: the node's own transform is ignored (glTF 2.0,
                // "Skins"), and the placement is the identity.
                if (n.skin < 0 || static_cast<size_t>(n.skin) >= ctx.model.skins.size())
                    missing(ctx, "skin", n.skin, ctx.model.skins.size(), label);
                skinned.push_back({out.placements.size(), n.skin, p.node, world});
                out.placements.push_back(
                    {static_cast<uint32_t>(n.mesh), Transform(), static_cast<uint32_t>(index)});
            } else if (std::optional<Transform> t = Transform::fromMatrix(world))
                out.placements.push_back(
                    {static_cast<uint32_t>(n.mesh), *t, static_cast<uint32_t>(index)});
            else
                ctx.warn(label +
                         ": its transform is singular (a scale of 0?) or too large: its "
                         "mesh is not placed");
        }
        if (n.camera != -1) {
            if (n.camera < 0 || static_cast<size_t>(n.camera) >= ctx.model.cameras.size())
                missing(ctx, "camera", n.camera, ctx.model.cameras.size(), label);
            cameras.push_back({n.camera, index, world,
                               describe("camera", static_cast<size_t>(n.camera),
                                        ctx.model.cameras[static_cast<size_t>(n.camera)].name) +
                                   " (" + label + ")"});
            // By default, the first camera Glint can use; those met before it are ignored with
            // a warning.
            if (firstCamera && !out.camera) {
                std::string problem;
                out.camera = nodeCamera(ctx, cameras.back(), problem);
                if (!out.camera) ctx.warn(problem + ": it is ignored");
            }
        }
        if (auto ext = n.extensions.find("KHR_lights_punctual");
            ext != n.extensions.end() && ext->second.IsObject() && ext->second.Has("light")) {
            const tinygltf::Value& v = ext->second.Get("light");
            if (!v.IsInt()) ctx.fail(label + ": its KHR_lights_punctual light must be an index");
            int light = v.GetNumberAsInt();
            if (light < 0 || static_cast<size_t>(light) >= ctx.model.lights.size())
                missing(ctx, "light", light, ctx.model.lights.size(), label);
            if (std::optional<LightSpec> l = nodeLight(ctx, light, world, label))
                out.lights.push_back(*l);
        }
        for (auto it = n.children.rbegin(); it != n.children.rend(); ++it)
            stack.push_back({*it, world, p.node});
    }
    if (!firstCamera) out.camera = chooseCamera(ctx, cameras, ctx.options.camera);
}

/// Reads every mesh a placement uses, once, after checking what they and their placements
/// need of memory; the meshes that skinned placements use with the joints and weights of
/// their vertices, into `weights` (by mesh).
void readMeshes(Context& ctx, Model& out, const std::vector<SkinnedPlacement>& skinned,
                Materials& materials, std::vector<VertexWeights>& weights) {
    const size_t meshes = ctx.model.meshes.size();
    out.meshes.resize(meshes);
    std::vector<std::optional<MeshCounts>> counts(meshes);
    for (const ModelPlacement& p : out.placements)
        if (!counts[p.mesh]) counts[p.mesh] = countMesh(ctx, static_cast<int>(p.mesh));
    // What is stored: each mesh, by the skin that poses it (-1: none). A mesh posed by a skin
    // and used otherwise too is copied (poseSkins).
    std::vector<int> skinOf(out.placements.size(), -1);
    for (const SkinnedPlacement& s : skinned) skinOf[s.placement] = s.skin;
    std::map<std::pair<uint32_t, int>, size_t> uses;  // placements of each stored mesh
    for (size_t i = 0; i < out.placements.size(); ++i) ++uses[{out.placements[i].mesh, skinOf[i]}];
    std::vector<bool> skinnedMesh(meshes);
    for (const SkinnedPlacement& s : skinned) skinnedMesh[out.placements[s.placement].mesh] = true;

    double meshBytes = 0, placed = 0, placedNormals = 0, placedUvs = 0, placedExtras = 0;
    double instances = 0;
    size_t maxPositions = 0, maxNormals = 0, maxGeneration = 0;
    for (size_t m = 0; m < meshes; ++m)
        if (counts[m]) {
            maxPositions = std::max(maxPositions, counts[m]->positions);
            maxNormals = std::max(maxNormals, counts[m]->normals);
            maxGeneration = std::max(maxGeneration, counts[m]->largestGeneration);
            if (skinnedMesh[m])  // the weights, and each vertex's matrix while posing
                meshBytes += double(counts[m]->positions) *
                             double(sizeof(VertexWeights::Vertex) + sizeof(Mat4));
        }
    for (const auto& [key, n] : uses) {
        const MeshCounts& c = *counts[key.first];
        meshBytes += c.bytes();
        // A mesh placed once becomes the scene's triangles; a mesh placed several times is
        // stored once and placed by instances (MeshPlacer), each the size of a shape.
        placed += double(c.triangles);
        placedNormals += double(c.normalTriangles);
        placedUvs += double(c.uvTriangles);
        placedExtras += double(c.extraTriangles);
        if (n > 1) instances += double(n);
    }
    // The scene's estimate per triangle, scaled: the counts may exceed size_t's range.
    const double perTriangle = double(Scene::estimateBytes(1000, 0, 0, 0, 0)) / 1000;
    const double perNormal = double(Scene::estimateBytes(1000, 0, 0, 1000, 0)) / 1000 - perTriangle;
    const double perUv = double(Scene::estimateBytes(1000, 0, 0, 0, 1000)) / 1000 - perTriangle;
    const double perInstance = double(Scene::estimateBytes(0, 0, 1000, 0, 0)) / 1000;
    const double perExtras = sizeof(TriangleExtras) + 2 * sizeof(uint32_t);
    double needed = double(decompressedBytes(ctx)) + meshBytes + placed * perTriangle +
                    placedNormals * perNormal + placedUvs * perUv + placedExtras * perExtras +
                    instances * perInstance +
                    double(std::max(meshPlacementBytes(maxPositions, maxNormals),
                                    tangentGenerationBytes(maxGeneration)));
    size_t available = memoryAvailable(ctx.options.limits);
    if (available > 0 && needed > double(available))
        ctx.fail("the model needs about " + formatBytes(needed) + " of memory (" +
                 std::to_string(static_cast<unsigned long long>(placed)) +
                 " triangles stored), more than the " + formatBytes(double(available)) +
                 " available");
    weights.resize(meshes);
    // Morph weights are the node's (animated, or its own `weights`), else the mesh's: those of
    // the first node that places the mesh, and a mesh is read once.
    std::vector<const std::vector<double>*> morph(meshes, nullptr);
    std::vector<bool> seen(meshes);
    for (const ModelPlacement& p : out.placements) {
        if (seen[p.mesh]) continue;
        seen[p.mesh] = true;
        const tinygltf::Node& node = ctx.model.nodes[p.node];
        if (p.node < ctx.animated.size() && ctx.animated[p.node].weights)
            morph[p.mesh] = &*ctx.animated[p.node].weights;
        else if (!node.weights.empty())
            morph[p.mesh] = &node.weights;
    }
    for (size_t i = 0; i < meshes; ++i)
        if (counts[i])
            out.meshes[i] = readMesh(ctx, static_cast<int>(i), *counts[i], materials,
                                     skinnedMesh[i] ? &weights[i] : nullptr, morph[i]);
}

}  // namespace
}  // namespace gltf

/// The parsed file, its images as decoded so far, and the warnings given.
struct GltfDocument::Impl {
    Impl(const std::string& fileName, const GltfOptions& options_)
        : file(fileName), options(options_), ctx(file, warnings, options), materials(ctx) {}

    /// Moves the warnings given since the last call into `out`, each message once per asset.
    void report(std::vector<Diagnostic>& out) {
        for (Diagnostic& d : warnings)
            if (reported.insert(d.message).second) out.push_back(std::move(d));
        warnings.clear();
    }

    std::string file;
    GltfOptions options;
    std::vector<Diagnostic> warnings;
    gltf::Context ctx;
    gltf::Materials materials;
    std::vector<FormatExtension> extensions;
    std::vector<ModelAnimation> animations;
    std::set<std::string> reported;
};

GltfDocument::GltfDocument(std::string_view bytes, const std::string& fileName,
                           std::vector<Diagnostic>& warnings, const GltfOptions& options)
    : impl_(std::make_unique<Impl>(fileName, options)) {
    try {
        gltf::parseContainer(impl_->ctx, bytes);
        gltf::checkAsset(impl_->ctx);
        gltf::applyVariant(impl_->ctx, options.variant);
        impl_->extensions = gltf::reportExtensions(impl_->ctx, options.variant);
        impl_->animations = gltf::listAnimations(impl_->ctx);
    } catch (...) {
        impl_->report(warnings);
        throw;
    }
    impl_->report(warnings);
}

GltfDocument::~GltfDocument() = default;

const std::vector<ModelAnimation>& GltfDocument::animations() const { return impl_->animations; }

Model GltfDocument::pose(const ModelTime& time, std::vector<Diagnostic>& warnings) {
    gltf::Context& ctx = impl_->ctx;
    Model out;
    try {
        out.name = impl_->file;
        out.extensions = impl_->extensions;
        out.animations = impl_->animations;
        out.variants = gltf::materialVariants(ctx);
        ctx.animated.clear();
        gltf::unplayPointers(ctx);  // the last pose's animated properties, as the file has them
        if (time.playing()) out.animation = gltf::playAnimation(ctx, time, out.posed);
        for (int m : ctx.pointedMaterials) impl_->materials.forget(m);  // now or before animated
        if (ctx.pointed.empty()) ctx.pointedMaterials.clear();
        std::vector<gltf::SkinnedPlacement> skinned;
        gltf::walkNodes(ctx, out, skinned);
        std::vector<gltf::VertexWeights> weights;
        gltf::readMeshes(ctx, out, skinned, impl_->materials, weights);
        if (!skinned.empty()) gltf::poseSkins(ctx, out, skinned, weights);
    } catch (...) {
        impl_->report(warnings);
        throw;
    }
    impl_->report(warnings);
    return out;
}

Model parseGltf(std::string_view bytes, const std::string& fileName,
                std::vector<Diagnostic>& warnings, const GltfOptions& options) {
    GltfDocument asset(bytes, fileName, warnings, options);
    return asset.pose(options.time, warnings);
}

std::shared_ptr<GltfDocument> openGltf(const std::string& path, std::vector<Diagnostic>& warnings,
                                       const GltfOptions& options) {
    if (std::string problem = inputFileProblem(path); !problem.empty())
        throw SceneError({path, 0, 0}, "cannot read glTF: " + problem);
    try {
        MappedFile file(path);
        return std::make_shared<GltfDocument>(file.text(), path, warnings, options);
    } catch (const std::system_error& e) {
        throw SceneError({path, 0, 0},
                         std::string("cannot read glTF: ") + std::strerror(e.code().value()));
    }
}

Model loadGltf(const std::string& path, std::vector<Diagnostic>& warnings,
               const GltfOptions& options) {
    return openGltf(path, warnings, options)->pose(options.time, warnings);
}

}  // namespace glint
