// Glint's extensions of the scene format: materials (transmission, ior, roughness), area
// lights, the environment map, sampling, the thin lens, the integrator and the shapes
// (docs/scene-format.md).

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "glint/geometry/polygon.h"
#include "glint/io/course/course_parser.h"
#include "glint/io/image/environment_io.h"
#include "glint/render/integrators/integrator.h"

namespace glint::course {

void Parser::cmdIor() {
    double n = real(1);
    if (!(n > 0)) fail(1, "ior must be positive, got " + quoted(1));
    builder_.editMaterial().ior = n;
}

void Parser::cmdRoughness() {
    double a = real(1);
    if (!(a >= 0 && a <= 1)) fail(1, "roughness must be between 0 and 1, got " + quoted(1));
    // Below this the GGX lobe is a mirror in all but round-off: treat it as one.
    builder_.editMaterial().roughness = a < 1e-4 ? 0 : a;
}

void Parser::cmdQuadLight() {
    const Transform& t = transform();
    LightSpec l;
    l.kind = LightSpec::Kind::Quad;
    l.position = checkedVertex(t.point(vec3(1)), 1);
    l.edge1 = t.vector(vec3(4));
    l.edge2 = t.vector(vec3(7));
    l.color = colour(10);
    Vec3 corners[4] = {l.position, l.position + l.edge1, l.position + l.edge1 + l.edge2,
                       l.position + l.edge2};
    for (int k = 1; k < 4; ++k)
        if (!withinCoordinateRange(corners[k]))
            fail(4, "the light reaches beyond the supported coordinate range (1e18)");
    double area = l.quadArea();
    if (!(area > 0) || !std::isfinite(area) || !(area > 1e-12 * length(l.edge1) * length(l.edge2)))
        fail(4, "quadLight edges must not be zero or parallel");
    builder_.addQuadLight(l);
}

void Parser::cmdEnvironment() {
    double scale = ntok_ >= 3 ? real(2) : 1;
    if (!(scale >= 0)) fail(2, "environment scale must not be negative, got " + quoted(2));
    double rotation = ntok_ == 4 ? number(3) : 0;  // degrees, as for `rotate`
    if (!limits_.readFiles)
        fail(1, "environment map " + quoted(1) + " is not read: reading files is off");
    HdrImage image;
    try {
        image = loadEnvironmentImage(scenePath(tok_[1].text), limits_);
    } catch (const RenderError& e) {
        fail(1, e.what());
    }
    size_t bad = 0;
    for (float v : image.rgb) bad += !(v >= 0 && v <= static_cast<float>(kMaxRadiance));
    if (bad)
        warn(1, "environment map " + quoted(1) + " has " + std::to_string(bad) +
                    (bad == 1 ? " value" : " values") +
                    " that are negative, NaN or beyond 1e30: negative and NaN values read as 0, "
                    "larger ones as 1e30");
    if (environmentLine_)
        warn(0,
             "a second environment replaces the one on line " + std::to_string(environmentLine_));
    environmentLine_ = line_;
    scene().environment = std::make_shared<const EnvironmentMap>(
        image.width, image.height, std::move(image.rgb), scale, rotation);
}

void Parser::cmdFilter() {
    FilterSpec f;
    if (tok_[1].text == "box")
        f.kind = FilterSpec::Kind::Box;
    else if (tok_[1].text == "gaussian")
        f.kind = FilterSpec::Kind::Gaussian;
    else
        fail(1, "unknown filter " + quoted(1) + " (box or gaussian)");
    f.radius = FilterSpec::defaultRadius(f.kind);
    if (ntok_ == 3) {
        f.radius = real(2);
        if (!(f.radius >= 0.5 && f.radius <= 4))
            fail(2, "filter radius must be 0.5 to 4 pixels, got " + quoted(2));
    }
    scene().filter = f;
}

void Parser::cmdLens() {
    double r = real(1);
    if (!(r >= 0)) fail(1, "aperture radius must not be negative, got " + quoted(1));
    double d = ntok_ == 3 ? real(2) : 0;
    if (ntok_ == 3 && !(d > 0)) fail(2, "focus distance must be positive, got " + quoted(2));
    builder_.setLens(r, d);
}

void Parser::cmdIntegrator() {
    if (!findIntegrator(tok_[1].text))
        fail(1, "unknown integrator " + quoted(1) + " (Glint has " + integratorNameList() + ")");
    scene().integrator = std::string(tok_[1].text);
}

// ---- Shape extensions ---------------------------------------------------------------------

void Parser::cmdPlane() {
    Vec3 point = vec3(1), normal = vec3(4);
    if (normal == Vec3(0)) fail(4, "plane normal must not be zero");
    const Transform& t = transform();
    if (!withinCoordinateRange(t.point(point)))
        fail(1,
             "the plane's point lies beyond the supported coordinate range (1e18) after the "
             "transform");
    std::optional<Plane> plane = Plane::make(point, normal, t);
    if (!plane) fail(4, "the plane's normal cannot be normalised after the transform");
    builder_.addPlane(*plane);
}

void Parser::cmdBox() {
    Vec3 a = vec3(1), b = vec3(4);
    for (int k = 0; k < 3; ++k)
        if (a[k] == b[k])
            fail(4 + k, std::string("box has zero extent along ") + "xyz"[k] +
                            ": both corners have " + "xyz"[k] + " = " + quoted(4 + k));
    addMoving([&] {
        builder_.addShape(ShapeKind::Box, boxPlacement(a, b), 1);
        return true;
    });
}

void Parser::cmdCylinder() {
    Vec3 a = vec3(1), b = vec3(4);
    double r = real(7);
    if (a == b) fail(4, "the cylinder's end points coincide: its axis has no direction");
    if (!(r > 0)) fail(7, "cylinder radius must be positive, got " + quoted(7));
    addMoving([&] {
        builder_.addShape(ShapeKind::Cylinder, cylinderPlacement(a, b, r), 1);
        return true;
    });
}

void Parser::cmdCone() {
    Vec3 a = vec3(1), b = vec3(5);
    double r0 = real(4), r1 = real(8);
    if (r0 < 0) fail(4, "cone radius must not be negative, got " + quoted(4));
    if (r1 < 0) fail(8, "cone radius must not be negative, got " + quoted(8));
    if (r0 == 0 && r1 == 0) fail(4, "cone radii must not both be zero");
    if (a == b) fail(5, "the cone's end points coincide: its axis has no direction");
    double k = 1;
    Mat4 placement = conePlacement(a, r0, b, r1, k);
    addMoving([&] {
        builder_.addShape(ShapeKind::Cone, placement, k);
        return true;
    });
}

void Parser::cmdDisk() {
    Vec3 c = vec3(1), n = vec3(4);
    double r = real(7);
    if (n == Vec3(0)) fail(4, "disk normal must not be zero");
    if (!(r > 0)) fail(7, "disk radius must be positive, got " + quoted(7));
    addMoving([&] {
        builder_.addShape(ShapeKind::Disk, diskPlacement(c, n, r), 1);
        return true;
    });
}

void Parser::cmdPolygon() {
    noteStillTriangles();
    const int n = ntok_ - 1;
    std::vector<uint32_t> index(static_cast<size_t>(n));
    std::vector<Vec3> points(static_cast<size_t>(n));
    for (int k = 0; k < n; ++k) {
        uint32_t v = vertexIndex(k + 1, vertices_.size(), "vertex", "vertices");
        for (int j = 0; j < k; ++j)
            if (index[static_cast<size_t>(j)] == v)
                fail(k + 1, "vertex index " + quoted(k + 1) + " appears twice in the polygon");
        index[static_cast<size_t>(k)] = v;
        points[static_cast<size_t>(k)] = vertices_[v];
    }
    PolygonTriangulation poly = triangulatePolygon(points);
    using Problem = PolygonTriangulation::Problem;
    const int at = poly.vertex + 1;  // the token of the vertex at fault
    auto edge = [&](int from) { return quoted(from + 1) + " to " + quoted((from + 1) % n + 1); };
    switch (poly.problem) {
        case Problem::None:
            break;
        case Problem::SamePosition:
            fail(at, "polygon vertex " + quoted(at) + " is at the same position as vertex " +
                         quoted(poly.other + 1));
        case Problem::ZeroArea:
            fail(0, "the polygon has zero area: its vertices lie on one line");
        case Problem::NonPlanar: {
            char off[32];
            std::snprintf(off, sizeof off, "%.2g%%", 100 * poly.offPlane);
            fail(at, "the polygon is not planar: vertex " + quoted(at) + " lies off its plane by " +
                         off + " of its size (at most 0.1% is allowed)");
        }
        case Problem::SelfIntersecting:
            fail(at, "the polygon's edges cross: the edge from vertex " + edge(poly.vertex) +
                         " meets the edge from vertex " + edge(poly.other));
    }
    const Transform& t = transform();
    std::vector<Vec3> world(static_cast<size_t>(n));
    for (int k = 0; k < n; ++k)
        world[static_cast<size_t>(k)] =
            checkedVertex(t.point(points[static_cast<size_t>(k)]), k + 1);
    // The polygon's normal shades all its triangles. Under a mirroring transform the vertex
    // order turns the other way, and the normal with it, as for `tri`.
    Mat4 m = t.matrix();
    double det = m.m[0][0] * (m.m[1][1] * m.m[2][2] - m.m[1][2] * m.m[2][1]) -
                 m.m[0][1] * (m.m[1][0] * m.m[2][2] - m.m[1][2] * m.m[2][0]) +
                 m.m[0][2] * (m.m[1][0] * m.m[2][1] - m.m[1][1] * m.m[2][0]);
    Vec3 normal = t.normal(poly.normal);
    normal = normal / maxComponent(abs(normal));  // no overflow or underflow in the length
    normal = normalize(normal) * (det < 0 ? -1.0 : 1.0);
    const Vec3 normals[3] = {normal, normal, normal};
    for (const auto& tri : poly.triangles) {
        Vec3 p[3] = {world[tri[0]], world[tri[1]], world[tri[2]]};
        addTriangle(p, isFinite(normal) ? normals : nullptr);
    }
}

}  // namespace glint::course
