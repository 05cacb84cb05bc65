// The course's commands (CSE167x homework 3): docs/scene-format.md, "Commands".

#include <algorithm>
#include <cmath>
#include <limits>
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
    if (!builder_.addSphere(center, radius))
        warn(4, "sphere of radius 0 is invisible and is skipped");
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
    if (builder_.popTransform()) return;
    const std::string what = "popTransform without a matching pushTransform";
    if (!lenient_) fail(0, what + " (--lenient ignores it)");
    warnRepeated("popTransform", what + " ignored", "");
}

void Parser::cmdDirectional() {
    Light l;
    l.kind = Light::Kind::Directional;
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
