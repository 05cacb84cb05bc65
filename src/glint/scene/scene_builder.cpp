#include "glint/scene/scene_builder.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "glint/geometry/shape_search.h"

namespace glint {
namespace {

/// The name of a shape kind in messages ("the box is ...").
const char* shapeName(ShapeKind kind) {
    switch (kind) {
        case ShapeKind::Box:
            return "box";
        case ShapeKind::Cylinder:
            return "cylinder";
        case ShapeKind::Cone:
            return "cone";
        case ShapeKind::Disk:
            return "disk";
        default:
            return "shape";
    }
}

}  // namespace

bool SceneBuilder::popTransform() {
    if (stack_.size() == 1) return false;
    stack_.pop_back();
    transformValid_ = false;
    return true;
}

const Transform& SceneBuilder::bakeTransform() {
    if (!transformValid_) {
        transform_ = Transform::fromMatrix(stack_.back());
        transformValid_ = true;
    }
    if (!transform_) throw BuildError("the current transform is singular or not finite");
    return *transform_;
}

void SceneBuilder::addPointLight(const Vec3& position, const Vec3& colour) {
    LightSpec l;
    l.kind = LightSpec::Kind::Point;
    l.position = position;
    l.color = colour;
    l.attenuation = attenuation_;
    scene_->lights.push_back(l);
}

void SceneBuilder::addQuadLight(const LightSpec& quad) {
    scene_->lights.push_back(quad);
    Material m;
    m.ambient = Vec3(0);
    m.emission = quad.color;
    m.frontEmissionOnly = true;
    uint32_t id = addMaterial(m);
    const Vec3 p = quad.position, a = p + quad.edge1, b = p + quad.edge1 + quad.edge2,
               c = p + quad.edge2;
    scene_->primitives.addTriangle(p, a, b, nullptr, id);
    scene_->primitives.addTriangle(p, b, c, nullptr, id);
}

bool SceneBuilder::addSphere(const Vec3& center, double radius) {
    Sphere s{center, radius, transform()};
    if (radius == 0) return false;
    Bounds3f b = s.bounds();
    if (!withinCoordinateRange(Vec3(b.lo)) || !withinCoordinateRange(Vec3(b.hi)))
        throw BuildError("the sphere reaches beyond the supported coordinate range (1e18)");
    if (!(sphereSearch(s).largestEntry() <= kMaxCoordinate))
        throw BuildError("the sphere is too thin: a semi-axis is below 1e-18 after the transform");
    scene_->primitives.addSphere(s, materialId());
    return true;
}

void SceneBuilder::addShape(ShapeKind kind, const Mat4& objectFromCanonical, double k) {
    const Transform& current = transform();  // a singular current transform is reported first
    std::optional<Transform> t = Transform::fromMatrix(current.matrix() * objectFromCanonical);
    const std::string the = std::string("the ") + shapeName(kind);
    if (!t) throw BuildError(the + " is degenerate after the transform (too thin or too large)");
    Shape shape{kind, k, *t};
    Bounds3f b = shape.bounds();
    if (!withinCoordinateRange(Vec3(b.lo)) || !withinCoordinateRange(Vec3(b.hi)))
        throw BuildError(the + " reaches beyond the supported coordinate range (1e18)");
    if (!(shape.search().largestEntry() <= kMaxCoordinate))
        throw BuildError(the + " is too thin: a dimension is below 1e-18 after the transform");
    scene_->primitives.addShape(shape, materialId());
}

std::unique_ptr<Scene> SceneBuilder::finish(std::vector<Diagnostic>* warnings) {
    placer_.place(*scene_, warnings);
    if (scene_->camera) {
        scene_->camera->apertureRadius = apertureRadius_;
        scene_->camera->focusDistance = focusDistance_;
    }
    return std::move(scene_);
}

void SceneBuilder::attachPbr() {
    PbrMaterial p = *pbr_;
    const Material& m = material_;
    p.baseColor = m.diffuse;
    p.roughness = std::sqrt(std::clamp(m.roughness, 0.0, 1.0));  // GGX alpha = roughness^2
    p.emissive = m.emission;
    p.transmission =
        std::clamp((m.transmission.x + m.transmission.y + m.transmission.z) / 3, 0.0, 1.0);
    p.ior = m.ior;
    p.doubleSided = true;  // the scene format's surfaces have two sides
    // A course `texture` image replaces the diffuse colour: it is the base colour then.
    if (!p.baseColorTexture && m.texture != 0) {
        const Texture& t = scene_->texture(m.texture);
        if (t.kind == Texture::Kind::Image && t.image) {
            p.baseColorTexture.image = t.image;
            p.baseColorTexture.wrapS = p.baseColorTexture.wrapT = t.wrap;
            p.baseColor = Vec3(1);
        }
    }
    auto& all = scene_->pbrMaterials;
    material_.pbr = !all.empty() && all.back() == p ? static_cast<uint32_t>(all.size())
                                                    : scene_->addPbrMaterial(std::move(p));
}

}  // namespace glint
