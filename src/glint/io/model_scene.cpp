#include "glint/io/model_scene.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>

#include "glint/io/obj_loader.h"
#include "glint/scene/mesh.h"

namespace glint {
namespace {

constexpr double kFovyDegrees = 40;
/// The bounding sphere fills at most this fraction of the narrower field of view.
constexpr double kFill = 0.9;

std::string format(const Vec3& v) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "(%.4g, %.4g, %.4g)", v.x, v.y, v.z);
    return buf;
}

Light directional(const Vec3& towards, double intensity) {
    Light l;
    l.kind = Light::Kind::Directional;
    l.direction = normalize(towards);
    l.color = Vec3(intensity);
    return l;
}

}  // namespace

bool isModelFile(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext == ".obj";
}

std::string frameModel(Scene& scene, const std::string& name) {
    Bounds3f b = scene.primitives.bounds();
    if (b.empty()) throw SceneError({name, 0, 0}, "the model has no faces of non-zero area");
    Vec3 lo(b.lo), hi(b.hi);
    Vec3 center = (lo + hi) * 0.5;
    double radius = 0.5 * length(hi - lo);
    if (!(radius > 0)) radius = 1;

    // The sphere fits when the camera is radius / sin(half angle) away, for the narrower of the
    // vertical and horizontal fields of view.
    double halfV = kFovyDegrees * std::numbers::pi / 360;
    double halfH = std::atan(std::tan(halfV) * scene.width / scene.height);
    double half = std::min(halfV, halfH);
    double distance = radius / (kFill * std::sin(half));
    Vec3 eye = center + normalize(Vec3{0, 0.5, 1}) * distance;
    scene.camera = CameraSpec{eye, center, {0, 1, 0}, kFovyDegrees};

    // A key light from the upper left and a dimmer fill from the right.
    scene.lights.push_back(directional({-1, 1.6, 1.2}, 0.75));
    scene.lights.push_back(directional({1.2, 0.6, 0.8}, 0.3));
    scene.background = Background{{1, 1, 1}, {0.45, 0.65, 0.95}};

    // The floor, a thousandth of the model's size under its lowest point, so that a flat
    // bottom does not coincide with it.
    double floorY = lo.y - 1e-3 * radius;
    Material floor;
    floor.diffuse = Vec3(0.55);
    floor.ambient = floor.diffuse * kMtlAmbientLight;
    if (auto plane = Plane::make({center.x, floorY, center.z}, {0, 1, 0}, Transform()))
        scene.primitives.addPlane(*plane, scene.addMaterial(floor));

    char floorText[64];
    std::snprintf(floorText, sizeof floorText, "%.4g", floorY);
    return "a camera at " + format(eye) + " looking at " + format(center) +
           " (fovy 40), a key and a fill directional light, a grey floor at y = " + floorText +
           " and a light grey material where the model has none";
}

ModelScene loadModelScene(const std::string& path, std::vector<Diagnostic>& warnings, int width,
                          int height, const LoadLimits& limits) {
    ModelScene out;
    out.scene = std::make_unique<Scene>();
    Scene& scene = *out.scene;
    scene.width = width;
    scene.height = height;
    {
        ObjOptions options;
        options.limits = limits;
        MeshData mesh = loadObj(path, warnings, options);  // freed before the BVH is built
        // Faces without an MTL material: a light grey, lit like MTL materials without Ka.
        Material grey;
        grey.diffuse = Vec3(0.7);
        grey.ambient = grey.diffuse * kMtlAmbientLight;
        addMesh(scene, mesh, Transform(), scene.addMaterial(grey));
    }
    out.assumptions = frameModel(scene, path);
    return out;
}

}  // namespace glint
