// The course's commands (CSE167x homework 3): docs/scene-format.md, "Commands".

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "glint/io/course/course_parser.h"
#include "glint/io/image/image_io.h"

namespace glint::course {

void Parser::cmdSize() {
    long long w = integer(1, 1, kMaxImageSide);
    long long h = integer(2, 1, kMaxImageSide);
    if (w * h > kMaxImagePixels)
        fail(2, "image of " + std::to_string(w) + " x " + std::to_string(h) +
                    " pixels is too large (at most " + std::to_string(kMaxImagePixels) +
                    " pixels)");
    scene().width = static_cast<int>(w);
    scene().height = static_cast<int>(h);
}

void Parser::cmdMaxDepth() {
    long long d = integer(1, 0, std::numeric_limits<long long>::max());
    if (d > kMaxDepthLimit) {
        warn(1, "maxdepth " + std::to_string(d) + " is more than Glint traces; using " +
                    std::to_string(kMaxDepthLimit));
        d = kMaxDepthLimit;
    }
    scene().maxDepth = static_cast<int>(d);
}

void Parser::cmdOutput() {
    scene().output = std::string(tok_[1].text);
    if (!imageFormatFor(scene().output))
        warn(1, "Glint cannot write " + quoted(1) + ": use a " + kImageExtensions +
                    " name here or choose one with -o");
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
    if (scene().camera)
        warn(0, "a second camera replaces the one on line " + std::to_string(cameraLine_));
    scene().camera = c;
    cameraLine_ = line_;
}

void Parser::cmdSphere() {
    Vec3 center = vec3(1);
    double radius = real(4);
    if (radius < 0) fail(4, "sphere radius must not be negative, got " + quoted(4));
    addMoving([&] {
        if (builder_.addSphere(center, radius)) return true;
        warn(4, "sphere of radius 0 is invisible and is skipped");
        return false;
    });
}

void Parser::cmdMotion() {
    Motion m;
    m.frame = builder_.matrix();
    m.velocity = vec3(1);
    if (ntok_ == 8) {
        m.axis = vec3(4);
        m.degreesPerSecond = number(7);
        if (m.axis == Vec3(0)) fail(4, "rotation axis must not be zero");
    } else if (ntok_ != 4) {
        fail(0, "motion takes 3 numbers (a velocity) or 7 (and an axis and degrees per second)");
    }
    motion_.back() = m;
}

std::vector<Mat4> Parser::movedTransforms() {
    const std::optional<Motion>& m = motion_.back();
    if (!m) return {};
    const std::optional<Mat4> inverseFrame = inverse(m->frame);
    if (!inverseFrame) fail(0, "the transform a motion acts in is singular");
    // At time tau the motion's translation and turn act where `motion` was given, before the
    // transforms that came after it.
    auto at = [&](double tau) {
        const Vec3 d = m->velocity * tau;
        return m->frame * Mat4::translate(d.x, d.y, d.z) *
               Mat4::rotate(m->axis.x, m->axis.y, m->axis.z, m->degreesPerSecond * tau) *
               *inverseFrame * builder_.matrix();
    };
    std::vector<Mat4> out;
    if (!time_.blurs()) {
        out.push_back(at(time_.seconds.value_or(0)));
    } else {
        for (int k = 0; k < time_.shutterKeys; ++k) out.push_back(at(time_.keyTime(k)));
    }
    return out;
}

void Parser::addMoving(const std::function<bool()>& add) {
    const std::vector<Mat4> keys = movedTransforms();
    if (keys.empty()) {
        add();
        return;
    }
    std::vector<Transform> path;
    for (const Mat4& k : keys) {
        std::optional<Transform> t = Transform::fromMatrix(k);
        if (!t) fail(0, "the motion makes the transform singular or too large");
        path.push_back(*t);
    }
    const Primitives& prims = builder_.scene().primitives;
    const uint32_t spheres = prims.sphereCount(), shapes = prims.shapeCount();
    builder_.pushTransform();
    builder_.setMatrix(keys.front());
    const bool added = add();
    builder_.popTransform();
    if (!added || path.size() < 2) return;
    uint32_t id = prims.triangleCount() + prims.sphereCount() - 1;
    if (prims.sphereCount() == spheres && prims.shapeCount() > shapes)
        id = prims.triangleCount() + prims.sphereCount() + prims.shapeCount() - 1;
    builder_.scene().primitives.setMotion(id, MotionPath(path));
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

void Parser::noteStillTriangles() {
    if (!motion_.back() || warnedStillTriangles_) return;
    warnedStillTriangles_ = true;
    warn(0, std::string(tok_[0].text) +
                ": triangles do not follow a motion (they stay where the transform puts them); a "
                "mesh that moves belongs in a mesh file, placed by `mesh` under the motion "
                "(reported once)");
}

void Parser::cmdTri() {
    noteStillTriangles();
    uint32_t i[3];
    for (int k = 0; k < 3; ++k) i[k] = vertexIndex(k + 1, vertices_.size(), "vertex", "vertices");
    const Transform& t = transform();
    Vec3 p[3];
    for (int k = 0; k < 3; ++k) p[k] = checkedVertex(t.point(vertices_[i[k]]), k + 1);
    addTriangle(p, nullptr);
}

void Parser::cmdTriNormal() {
    noteStillTriangles();
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
    builder_.applyTransform(Mat4::translate(v.x, v.y, v.z));
}

void Parser::cmdRotate() {
    Vec3 axis = vec3(1);
    double degrees = number(4);
    if (axis == Vec3(0)) fail(1, "rotation axis must not be zero");
    builder_.applyTransform(Mat4::rotate(axis.x, axis.y, axis.z, degrees));
}

void Parser::cmdScale() {
    Vec3 s = vec3(1);
    for (int k = 0; k < 3; ++k)
        if (s[k] == 0) fail(k + 1, "scale by zero would make the transform singular");
    builder_.applyTransform(Mat4::scale(s.x, s.y, s.z));
}

void Parser::cmdPopTransform() {
    if (builder_.popTransform()) {
        motion_.pop_back();
        return;
    }
    const std::string what = "popTransform without a matching pushTransform";
    if (!lenient_) fail(0, what + " (--lenient ignores it)");
    warnRepeated("popTransform", what + " ignored", "");
}

void Parser::cmdDirectional() {
    LightSpec l;
    l.kind = LightSpec::Kind::Directional;
    Vec3 d = transform().vector(vec3(1));
    double len = length(d);
    if (!(len > 0) || !std::isfinite(len)) fail(1, "light direction must not be zero");
    l.direction = d / len;
    l.color = colour(4);
    builder_.addLight(l);
}

void Parser::cmdPoint() {
    Vec3 position = transform().point(vec3(1));
    builder_.addPointLight(position, colour(4));
    if (pointLights_++ == 0) firstPointLine_ = line_;
}

// A point light within a cone (glTF's spot light): at x y z, shining along dx dy dz, fully
// within `inner` degrees of that axis, not at all beyond `outer`, fading between; attenuated
// as point lights are.
void Parser::cmdSpot() {
    LightSpec l;
    l.kind = LightSpec::Kind::Spot;
    l.position = transform().point(vec3(1));
    const Vec3 axis = transform().vector(vec3(4));
    const double len = length(axis);
    if (!(len > 0) || !std::isfinite(len)) fail(4, "spot light direction must not be zero");
    l.axis = axis / len;
    l.color = colour(7);
    const double inner = real(10), outer = real(11);
    if (!(inner >= 0)) fail(10, "the inner cone angle must be 0 to 90 degrees");
    if (!(outer > inner && outer <= 90))
        fail(11, "the outer cone angle must be more than the inner one and at most 90 degrees");
    l.cosInner = std::cos(inner * std::numbers::pi / 180);
    l.cosOuter = std::cos(outer * std::numbers::pi / 180);
    l.attenuation = builder_.attenuation();
    builder_.addLight(l);
    if (pointLights_++ == 0) firstPointLine_ = line_;
}

void Parser::cmdAttenuation() {
    Vec3 a = vec3(1);
    for (int k = 0; k < 3; ++k)
        if (a[k] < 0) fail(k + 1, "attenuation coefficients must not be negative");
    if (a == Vec3(0)) fail(1, "attenuation coefficients must not all be zero");
    if (pointLights_ > 0 && !(a == builder_.attenuation()) && !warnedAttenuation_) {
        // The point lights above keep the attenuation they were declared with.
        warn(0,
             "attenuation applies only to point lights declared after it: " +
                 (pointLights_ == 1
                      ? "the one on line " + std::to_string(firstPointLine_) + " keeps its own"
                      : "the " + std::to_string(pointLights_) + " declared before it, from line " +
                            std::to_string(firstPointLine_) + ", keep theirs") +
                 " (reported once)");
        warnedAttenuation_ = true;
    }
    builder_.setAttenuation(a);
}

void Parser::cmdShininess() {
    double s = real(1);
    if (s < 0) fail(1, "shininess must not be negative, got " + quoted(1));
    builder_.editMaterial().shininess = s;
}

void Parser::cmdBackground() {
    scene().background.down = colour(1);
    scene().background.up = ntok_ == 7 ? colour(4) : scene().background.down;
}

}  // namespace glint::course
