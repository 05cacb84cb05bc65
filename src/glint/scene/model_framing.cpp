#include "glint/scene/model_framing.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "glint/scene/scene_builder.h"

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

std::string frameModel(Scene& scene, const std::string& name, Framing framing) {
    Bounds3f b = scene.primitives.bounds();
    if (b.empty()) throw SceneError({name, 0, 0}, "the model has no faces of non-zero area");
    Vec3 lo(b.lo), hi(b.hi);
    Vec3 center = (lo + hi) * 0.5;
    double radius = 0.5 * length(hi - lo);
    if (!(radius > 0)) radius = 1;

    std::string camera, lights, floor;
    if (framing.camera) {
        // The sphere fits when the camera is radius / sin(half angle) away, for the narrower
        // of the vertical and horizontal fields of view.
        double halfV = kFovyDegrees * std::numbers::pi / 360;
        double halfH = std::atan(std::tan(halfV) * scene.width / scene.height);
        double half = std::min(halfV, halfH);
        double distance = radius / (kFill * std::sin(half));
        Vec3 eye = center + normalize(Vec3{0, 0.5, 1}) * distance;
        scene.camera = CameraSpec{eye, center, {0, 1, 0}, kFovyDegrees};
        camera = "a camera at " + format(eye) + " looking at " + format(center) + " (fovy 40)";
        scene.background = Background{{1, 1, 1}, {0.45, 0.65, 0.95}};

        // The floor, a thousandth of the model's size under its lowest point, so that a flat
        // bottom does not coincide with it.
        double floorY = lo.y - 1e-3 * radius;
        Material grey;
        grey.diffuse = Vec3(0.55);
        grey.ambient = grey.diffuse * kMtlAmbientLight;
        if (auto plane = Plane::make({center.x, floorY, center.z}, {0, 1, 0}, Transform()))
            scene.primitives.addPlane(*plane, scene.addMaterial(grey));
        char floorText[64];
        std::snprintf(floorText, sizeof floorText, "%.4g", floorY);
        floor = std::string("a grey floor at y = ") + floorText;
    }
    if (framing.lights) {
        // A key light from the upper left and a dimmer fill from the right.
        scene.lights.push_back(directional({-1, 1.6, 1.2}, 0.75));
        scene.lights.push_back(directional({1.2, 0.6, 0.8}, 0.3));
        lights = "a key and a fill directional light";
    }
    if (framing.camera && framing.lights)
        return camera + ", " + lights + ", " + floor +
               " and a light grey material where the model has none";
    if (framing.camera) return camera + ", " + floor + " and a sky";
    return lights;
}

namespace {

/// The light grey of faces without a material of the file's, lit like MTL materials without Ka.
Material lightGrey() {
    Material grey;
    grey.diffuse = Vec3(0.7);
    grey.ambient = grey.diffuse * kMtlAmbientLight;
    return grey;
}

}  // namespace

ModelScene frameModelScene(const Model& model, int width, int height) {
    SceneBuilder builder;
    Scene& settings = builder.scene();
    settings.width = width > 0 ? width : 640;
    settings.height = height > 0 ? height : 480;
    placeModel(builder, model, Transform(), builder.addMaterial(lightGrey()));
    Framing framing;
    std::string has;  // what the file brought, for the note
    if (model.camera) {
        settings.camera = model.camera->spec;
        framing.camera = false;
        has = "its " + model.camera->description;
        // The file's camera knows its picture's shape, unless the command line says.
        if (width <= 0 && model.camera->aspectRatio > 0)
            settings.height = static_cast<int>(std::clamp(
                std::lround(settings.width / model.camera->aspectRatio), 1L, long(kMaxImageSide)));
    }
    if (!model.lights.empty()) {
        for (const Light& light : model.lights) builder.addLight(light);
        framing.lights = false;
        has = std::to_string(model.lights.size()) +
              (model.lights.size() == 1 ? " light" : " lights") + " of its own";
    }
    ModelScene out;
    out.scene = builder.finish();  // places the meshes: the scene's bounds are known now
    Scene& scene = *out.scene;
    const std::string& path = model.name;
    if (!framing.camera && !framing.lights) {
        if (scene.primitives.bounds().empty())
            throw SceneError({path, 0, 0}, "the model has no faces of non-zero area");
        return out;
    }
    std::string assumed = frameModel(scene, path, framing);
    if (framing.camera && framing.lights)
        out.note = path + " has no camera or lights: framing it with " + assumed;
    else if (framing.camera)
        out.note = path + " has no camera: framing it with " + assumed + " (and " + has + ")";
    else
        out.note = path + " has no lights: lighting it with " + assumed + " (and " + has + ")";
    return out;
}

}  // namespace glint
