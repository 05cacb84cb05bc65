#include "glint/scene/model_framing.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "glint/scene/scene_builder.h"
#include "glint/scene/studio_environment.h"

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

std::string format(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.4g", v);
    return buf;
}

LightSpec directional(const Vec3& towards, double intensity) {
    LightSpec l;
    l.kind = LightSpec::Kind::Directional;
    l.direction = normalize(towards);
    l.color = Vec3(intensity);
    return l;
}

/// The model's bounds, centre and bounding-sphere radius. Throws if it has no geometry.
struct Extent {
    Vec3 lo, hi, center;
    double radius;
    /// Where the ground goes: a thousandth of the model's size under its lowest point, so that
    /// a flat bottom does not coincide with it.
    double groundY() const { return lo.y - 1e-3 * radius; }
};

/// The extent of the model placed in `scene`, or of `frame` (Model::frameBounds) when set.
Extent extentOf(const Scene& scene, const std::string& name,
                const std::optional<Bounds3f>& frame = std::nullopt) {
    Bounds3f b = frame && !frame->empty() ? *frame : scene.primitives.bounds();
    if (b.empty()) throw SceneError({name, 0, 0}, "the model has no faces of non-zero area");
    Extent e{Vec3(b.lo), Vec3(b.hi), {}, 0};
    e.center = (e.lo + e.hi) * 0.5;
    e.radius = 0.5 * length(e.hi - e.lo);
    if (!(e.radius > 0)) e.radius = 1;
    return e;
}

/// Glint's camera for the model: on the +z/+y diagonal, the bounding sphere filling at most
/// kFill of the narrower field of view. Returns its description for the note.
std::string placeCamera(Scene& scene, const Extent& e) {
    // The sphere fits when the camera is radius / sin(half angle) away, for the narrower
    // of the vertical and horizontal fields of view.
    double halfV = kFovyDegrees * std::numbers::pi / 360;
    double halfH = std::atan(std::tan(halfV) * scene.width / scene.height);
    double half = std::min(halfV, halfH);
    double distance = e.radius / (kFill * std::sin(half));
    Vec3 eye = e.center + normalize(Vec3{0, 0.5, 1}) * distance;
    scene.camera = CameraSpec{eye, e.center, {0, 1, 0}, kFovyDegrees};
    return "a camera at " + format(eye) + " looking at " + format(e.center) + " (fovy 40)";
}

/// An infinite grey matte floor at the ground's height. Returns its description.
std::string placeFloor(Scene& scene, const Extent& e) {
    Material grey;
    grey.diffuse = Vec3(0.55);
    grey.ambient = grey.diffuse * kMtlAmbientLight;
    double y = e.groundY();
    if (auto plane = Plane::make({e.center.x, y, e.center.z}, {0, 1, 0}, Transform()))
        scene.primitives.addPlane(*plane, scene.addMaterial(grey));
    return "a grey floor at y = " + format(y);
}

void addKeyAndFill(Scene& scene) {
    // A key light from the upper left and a dimmer fill from the right.
    scene.lights.push_back(directional({-1, 1.6, 1.2}, 0.75));
    scene.lights.push_back(directional({1.2, 0.6, 0.8}, 0.3));
}

}  // namespace

std::string frameModel(Scene& scene, const std::string& name, Framing framing) {
    const Extent e = extentOf(scene, name, framing.bounds);
    std::string camera, lights, floor;
    if (framing.camera) {
        camera = placeCamera(scene, e);
        scene.background = Background{{1, 1, 1}, {0.45, 0.65, 0.95}};
        if (framing.floor) floor = placeFloor(scene, e);
    }
    if (framing.lights) {
        addKeyAndFill(scene);
        lights = "a key and a fill directional light";
    }
    // "X, Y and Z": the parts that were added.
    auto join = [](std::initializer_list<std::string> parts) {
        std::string s, last;
        for (const std::string& p : parts) {
            if (p.empty()) continue;
            if (!last.empty()) s += (s.empty() ? "" : ", ") + last;
            last = p;
        }
        return s.empty() ? last : s + " and " + last;
    };
    if (framing.camera && framing.lights)
        return join({camera, lights, floor, "a light grey material where the model has none"});
    if (framing.camera) return join({camera, floor, "a sky"});
    return lights;
}

const char* modelGroundName(ModelGround g) {
    switch (g) {
        case ModelGround::Shadow:
            return "shadow";
        case ModelGround::Floor:
            return "floor";
        default:
            return "none";
    }
}

namespace {

/// The light grey of faces without a material of the file's, lit like MTL materials without Ka.
Material lightGrey() {
    Material grey;
    grey.diffuse = Vec3(0.7);
    grey.ambient = grey.diffuse * kMtlAmbientLight;
    return grey;
}

/// The model placed in a new scene of the image's size, with its camera and lights.
struct Placed {
    std::unique_ptr<Scene> scene;
    std::string has;  ///< What the file brought, for the note ("its camera 0", "2 lights ...").
};

/// The model placed with its camera and lights, the lights' colours times `lightScale`.
Placed placeWithItsOwn(const Model& model, int width, int height, double lightScale = 1) {
    SceneBuilder builder;
    Scene& settings = builder.scene();
    settings.width = width > 0 ? width : 640;
    settings.height = height > 0 ? height : 480;
    placeModel(builder, model, Transform(), builder.addMaterial(lightGrey()));
    std::string has;
    if (model.camera) {
        settings.camera = model.camera->spec;
        settings.cameraMotion = model.cameraMotion;
        has = (model.camera->own ? "its " : "") + model.camera->description;
        // The file's camera knows its picture's shape, unless the command line says.
        if (width <= 0 && model.camera->aspectRatio > 0)
            settings.height = static_cast<int>(std::clamp(
                std::lround(settings.width / model.camera->aspectRatio), 1L, long(kMaxImageSide)));
    }
    if (!model.lights.empty()) {
        for (LightSpec light : model.lights) {
            light.color = light.color * lightScale;
            builder.addLight(light);
        }
        has = (has.empty() ? "" : has + " and ") + std::to_string(model.lights.size()) +
              (model.lights.size() == 1 ? " light" : " lights") + " of its own";
    }
    return {builder.finish(), has};  // places the meshes: the scene's bounds are known now
}

/// The classic look: what the model lacks of a camera (with a floor and a sky) and lights.
ModelScene classicScene(const Model& model, int width, int height, const ModelLook& look) {
    // The Whitted integrator's diffuse term is kd N.L without a Lambertian's 1/pi: a light of
    // colour c shows a white surface as c, so the model's physical lights are divided by pi.
    Placed placed = placeWithItsOwn(model, width, height, 1 / std::numbers::pi);
    Scene& scene = *placed.scene;
    const std::string& path = model.name;
    Framing framing{!model.camera, model.lights.empty(),
                    look.groundOrDefault() != ModelGround::None, model.frameBounds};
    ModelScene out;
    if (!framing.camera && !framing.lights) {
        extentOf(scene, path);  // throws for a model of nothing visible
    } else {
        std::string assumed = frameModel(scene, path, framing);
        if (framing.camera && framing.lights)
            out.note = path + " has no camera or lights: framing it with " + assumed;
        else if (framing.camera)
            out.note =
                path + " has no camera: framing it with " + assumed + " (and " + placed.has + ")";
        else
            out.note =
                path + " has no lights: lighting it with " + assumed + " (and " + placed.has + ")";
    }
    if (look.environment) {  // the command line's, over the sky
        scene.environment = *look.environment;
        if (!scene.environment) scene.background = Background{};
    }
    out.scene = std::move(placed.scene);
    return out;
}

/// The studio look (see the header).
ModelScene studioScene(const Model& model, int width, int height, const ModelLook& look) {
    Placed placed = placeWithItsOwn(model, width, height);
    Scene& scene = *placed.scene;
    const std::string& path = model.name;
    const Extent e = extentOf(scene, path, model.frameBounds);
    scene.integrator = "path";
    scene.spp = kStudioSpp;
    scene.maxDepth = kStudioMaxDepth;
    scene.bounces = kStudioBounces;
    scene.display = DisplaySpec{ToneMap::PbrNeutral, true};

    std::string camera;
    if (!model.camera) camera = placeCamera(scene, e);
    std::string staging;
    if (!look.environment) {
        scene.environment = studioEnvironment();
        staging = "in the studio environment";
    } else if (*look.environment) {
        scene.environment = *look.environment;
        staging = "in the environment map";
    } else {
        staging = "in the dark";
    }
    // Something must light it: its own lights, the environment, or its own glowing surfaces
    // (a room lit by its lamps' emissive panels, the Blender add-on's area lights).
    const bool glows = std::any_of(scene.materials.begin(), scene.materials.end(),
                                   [](const Material& m) { return !(m.emission == Vec3(0)); });
    if (!scene.environment && model.lights.empty() && !glows) {
        addKeyAndFill(scene);
        staging += ", lit by a key and a fill directional light,";
    }
    switch (look.groundOrDefault()) {
        case ModelGround::Shadow:
            scene.shadowCatcher = ShadowCatcher{e.groundY()};
            staging += " with a ground shadow at y = " + format(e.groundY());
            break;
        case ModelGround::Floor:
            staging += " on " + placeFloor(scene, e);
            break;
        case ModelGround::None:
            break;
    }
    if (staging.back() == ',') staging.pop_back();
    ModelScene out;
    out.note = camera.empty() ? "showing " + path + " " + staging
                              : path + " has no camera: framing it with " + camera +
                                    ", and showing it " + staging;
    if (!placed.has.empty()) out.note += " (and " + placed.has + ")";
    if (const double ev = modelExposure(scene, e.center, e.radius); ev != 0) {
        scene.display.exposure = ev;
        out.note += "; its lights are in physical units (candela, lux), " + format(std::exp2(-ev)) +
                    " times as bright as the studio: exposure " + format(ev) +
                    " (--exposure changes it)";
    }
    out.scene = std::move(placed.scene);
    return out;
}

}  // namespace

namespace {

/// Whether the point light at `p` sits inside emitting geometry (a bulb around it, as glTF
/// files model lamps): inside the box of the emitting primitives within `near` of it. Such a
/// light lights nothing but its bulb's inside.
bool inBulb(const Scene& scene, const Vec3& p, double near) {
    const Primitives& prims = scene.primitives;
    auto emits = [&](uint32_t m) {
        return m != Primitives::kMixedMaterials && !(scene.materials[m].emission == Vec3(0));
    };
    Bounds3f bulb;
    auto add = [&](Bounds3f b) {
        const Vec3 lo(b.lo), hi(b.hi);
        const Vec3 gap = max(max(lo - p, p - hi), Vec3(0));
        if (length(gap) <= near) bulb.extend(b);
    };
    for (uint32_t id = 0; id < prims.boundedCount(); ++id) {
        if (prims.isInstance(id)) {
            const Primitives& mesh = prims.sharedMesh(prims.instanceMesh(id));
            const Transform& t = prims.instanceTransform(id);
            for (uint32_t k = 0; k < mesh.triangleCount(); ++k) {
                if (!emits(mesh.materialOf(k))) continue;
                Bounds3f b;
                for (const Vec3f& v : mesh.triangleVertices(k)) b.extend(Vec3f(t.point(Vec3(v))));
                add(b);
            }
        } else if (emits(prims.materialOf(id))) {
            add(prims.bounds(id));
        }
    }
    if (bulb.empty()) return false;
    const Vec3 lo(bulb.lo), hi(bulb.hi);
    return p.x > lo.x && p.y > lo.y && p.z > lo.z && p.x < hi.x && p.y < hi.y && p.z < hi.z;
}

}  // namespace

double modelExposure(const Scene& scene, const Vec3& at, double size) {
    // The radiance of a white matte surface at `at` facing each light: irradiance / pi.
    double lights = 0;
    for (const LightSpec& l : scene.lights) {
        const double power = luminance(l.color);
        if (l.kind == LightSpec::Kind::Directional) {
            lights += power;
        } else if (l.kind != LightSpec::Kind::Quad && !inBulb(scene, l.position, 0.1 * size)) {
            // Point and spot lights by the inverse square.
            const double d = std::max(length(l.position - at), 0.25 * size);
            lights += power / (l.attenuation.x + l.attenuation.y * d + l.attenuation.z * d * d);
        }
    }
    const double studio = luminance(studioEnvironment()->averageRadiance());
    const double ratio = lights / std::numbers::pi / studio;
    if (!(ratio > kPhysicalLightRatio) || !std::isfinite(ratio)) return 0;
    return -std::round(2 * std::log2(ratio)) / 2;
}

ModelScene frameModelScene(const Model& model, int width, int height, const ModelLook& look) {
    ModelScene out = look.studio ? studioScene(model, width, height, look)
                                 : classicScene(model, width, height, look);
    out.framed = true;
    out.extensions = model.extensions;
    out.animations = model.animations;
    out.variants = model.variants;
    out.animation = model.animation;
    if (!model.posed.empty()) {
        out.note += (out.note.empty() ? model.name + ": " : "; ") + "posed by " + model.posed +
                    ", framed for the whole animation";
    } else if (!model.animations.empty()) {
        const size_t n = model.animations.size();
        out.note += (out.note.empty() ? model.name + ": " : "; ") + "it has " + std::to_string(n) +
                    (n == 1 ? " animation" : " animations") +
                    ", not played (--frame N or --time-at SECONDS plays " +
                    (n == 1 ? "it" : "one, --animation chooses which") + ")";
    }
    return out;
}

}  // namespace glint
