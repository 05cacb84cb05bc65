#include "glint/scene/model.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <utility>
#include <vector>

#include "glint/core/parse_float.h"

namespace glint {

namespace {

constexpr std::string_view kOrbitPrefix = "orbit:";

/// The numbers of "orbit:THETA,PHI,RADIUS[,TX,TY,TZ]" after the prefix.
OrbitCamera parseOrbit(std::string_view text) {
    const std::string form = "expected orbit:THETA,PHI,RADIUS[,TX,TY,TZ] (degrees and scene units)";
    std::vector<double> v;
    while (true) {
        size_t comma = text.find(',');
        std::string_view item = text.substr(0, comma);
        double x = 0;
        auto [end, ec] = parseFloat(item.data(), item.data() + item.size(), x);
        if (item.empty() || ec != std::errc() || end != item.data() + item.size())
            throw std::invalid_argument(form + ": '" + std::string(item) + "' is not a number");
        if (!std::isfinite(x))
            throw std::invalid_argument(form + ": '" + std::string(item) + "' is not finite");
        v.push_back(x);
        if (comma == std::string_view::npos) break;
        text.remove_prefix(comma + 1);
    }
    if (v.size() != 3 && v.size() != 6)
        throw std::invalid_argument(form + ": got " + std::to_string(v.size()) + " numbers");
    OrbitCamera o{v[0], v[1], v[2], {}};
    if (v.size() == 6) o.target = {v[3], v[4], v[5]};
    if (!(o.radius > 0)) throw std::invalid_argument("the orbit's radius must be positive");
    if (!(o.phiDegrees > 0 && o.phiDegrees < 180))
        throw std::invalid_argument(
            "the orbit's phi must be strictly between 0 and 180 degrees (the eye straight above "
            "or below the target leaves +y up no meaning)");
    return o;
}

std::string number(double x) {
    std::ostringstream s;
    s << x;
    return s.str();
}

}  // namespace

CameraSpec OrbitCamera::spec() const {
    constexpr double kDegree = std::numbers::pi / 180;
    const double theta = thetaDegrees * kDegree, phi = phiDegrees * kDegree;
    const Vec3 direction(std::sin(phi) * std::sin(theta), std::cos(phi),
                         std::sin(phi) * std::cos(theta));
    return CameraSpec{target + direction * radius, target, {0, 1, 0}, 45};
}

std::string OrbitCamera::describe() const {
    return "the orbit camera theta " + number(thetaDegrees) + ", phi " + number(phiDegrees) +
           ", radius " + number(radius) + " around (" + number(target.x) + ", " + number(target.y) +
           ", " + number(target.z) + ")";
}

CameraChoice CameraChoice::parse(const std::string& text) {
    CameraChoice c;
    if (text.empty()) return c;
    if (text.starts_with(kOrbitPrefix)) {
        c.kind = Kind::Orbit;
        c.orbit = parseOrbit(std::string_view(text).substr(kOrbitPrefix.size()));
        return c;
    }
    if (text == "none") {
        c.kind = Kind::None;
        return c;
    }
    if (std::all_of(text.begin(), text.end(), [](char ch) { return ch >= '0' && ch <= '9'; })) {
        c.kind = Kind::Index;
        auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), c.index);
        if (ec != std::errc()) c.index = SIZE_MAX;  // beyond any file's cameras
        return c;
    }
    c.kind = Kind::Name;
    c.name = text;
    return c;
}

std::string CameraChoice::describe() const {
    switch (kind) {
        case Kind::Index:
            return "camera " + std::to_string(index);
        case Kind::Name:
            return "camera '" + name + "'";
        case Kind::None:
            return "no camera";
        case Kind::Orbit:
            return orbit.describe();
        default:
            return "the first camera";
    }
}

size_t Model::triangles() const {
    size_t n = 0;
    for (const ModelPlacement& p : placements) n += meshes[p.mesh].triangles.size();
    return n;
}

Bounds3f Model::bounds() const {
    Bounds3f b;
    for (const ModelPlacement& p : placements)
        for (const Vec3f& v : meshes[p.mesh].positions)
            b.extend(Vec3f(p.worldFromObject.point(Vec3(v))));
    return b;
}

Model singleMeshModel(MeshData mesh) {
    Model model;
    model.name = mesh.name;
    model.meshes.push_back(std::move(mesh));
    model.placements.push_back({0, Transform(), 0});
    return model;
}

void placeModel(SceneBuilder& builder, const Model& model, const Transform& worldFromModel,
                uint32_t defaultMaterial, const FileLoc& where, const std::string& what,
                const std::vector<Transform>* modelMotion) {
    // Placements at the model's origin take the scene's transform as it is: the transform an
    // OBJ file is placed by is exactly the scene's.
    const bool identity = worldFromModel.isIdentity();
    const bool modelMoves = modelMotion && modelMotion->size() > 1;
    for (const ModelPlacement& p : model.placements) {
        if (modelMoves || p.motion.size() > 1) {
            // Both paths sampled at the same evenly spaced times, and composed.
            const size_t n = std::max(modelMoves ? modelMotion->size() : 1, p.motion.size());
            const MotionPath outer(modelMoves ? *modelMotion : std::vector{worldFromModel});
            const MotionPath inner(p.motion.size() > 1 ? p.motion : std::vector{p.worldFromObject});
            std::vector<Transform> keys;
            for (size_t k = 0; k < n; ++k) {
                const float u = static_cast<float>(k) / static_cast<float>(n - 1);
                std::optional<Transform> t =
                    Transform::fromMatrix(outer.at(u).matrix() * inner.at(u).matrix());
                if (!t)
                    throw SceneError({model.name, 0, 0},
                                     "node " + std::to_string(p.node) +
                                         ": its moving transform, with the scene's, is singular "
                                         "or too large");
                keys.push_back(*t);
            }
            builder.placeMesh(model.meshes[p.mesh], keys.front(), defaultMaterial, where, what,
                              std::make_shared<const MotionPath>(keys));
            continue;
        }
        std::optional<Transform> t =
            identity ? p.worldFromObject
            : p.worldFromObject.isIdentity()
                ? worldFromModel
                : Transform::fromMatrix(worldFromModel.matrix() * p.worldFromObject.matrix());
        if (!t)
            throw SceneError({model.name, 0, 0},
                             "node " + std::to_string(p.node) +
                                 ": its transform, with the scene's, is singular or too large");
        builder.placeMesh(model.meshes[p.mesh], *t, defaultMaterial, where, what);
    }
}

}  // namespace glint
