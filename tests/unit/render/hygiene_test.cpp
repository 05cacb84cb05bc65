// Numeric hygiene (issue 4): whatever the scene, no NaN or Inf arises in the integrator (it
// would be repaired before the film, and counted: RayCounts::nonFinite) or reaches a pixel, and
// surfaces do not shadow themselves (acne) at very small or very large scales.

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "glint/io/course/course_loader.h"
#include "glint/render/renderer.h"

namespace glint {
namespace {

RenderResult renderText(const std::string& text, int threads = 2) {
    std::vector<Diagnostic> warnings;
    auto scene = parseCourseScene(text, "hygiene.test", warnings);
    scene->prepare();
    RenderOptions o;
    o.threads = threads;
    return render(*scene, o);
}

/// Pixels that are NaN or infinite in any channel.
int nonFinitePixels(const Film& f) {
    int bad = 0;
    for (int y = 0; y < f.height(); ++y)
        for (int x = 0; x < f.width(); ++x) bad += !isFinite(f.at(x, y));
    return bad;
}

/// A small scene around `body`, seen by `camera` (by default from +z, looking at the origin).
/// The size is odd so that the centre pixel's ray runs exactly along the view axis: it meets
/// the origin exactly, which the light-on-the-surface and head-on cases need.
std::string framed(const std::string& body,
                   const std::string& camera = "camera 0 0 5 0 0 0 0 1 0 40") {
    return "size 49 33\n" + camera + "\nmaxdepth 8\n" + body;
}

struct Case {
    const char* name;
    std::string text;
};

class FinitePixels : public testing::TestWithParam<Case> {};

TEST_P(FinitePixels, NoRadianceIsNonFiniteWhereItArisesAndEveryPixelIsFinite) {
    RenderResult r = renderText(GetParam().text);
    // The integrator repairs NaN and Inf before the film, so the pixels alone cannot tell:
    // the count of repairs can.
    EXPECT_EQ(r.rays.nonFinite, 0u) << GetParam().name;
    EXPECT_EQ(nonFinitePixels(r.film), 0) << GetParam().name;
}

const std::string kQuad =
    "vertex -2 -2 0\nvertex 2 -2 0\nvertex 2 2 0\nvertex -2 2 0\ntri 0 1 2\ntri 0 2 3\n";

INSTANTIATE_TEST_SUITE_P(
    Hazards, FinitePixels,
    testing::Values(
        Case{"degenerate_triangles",
             framed("point 1 1 3 1 1 1\ndiffuse 1 1 1\n" + kQuad +
                    "vertex 0 0 1\nvertex 1 1 1\nvertex 2 2 1\ntri 4 5 6\ntri 4 4 5\n")},
        Case{"zero_radius_sphere",
             framed("point 1 1 3 1 1 1\ndiffuse 1 1 1\nsphere 0 0 0 0\n" + kQuad)},
        Case{"zero_length_vertex_normals",
             framed("point 1 1 3 1 1 1\ndiffuse 1 1 1\nspecular 0.5 0.5 0.5\nshininess 10\n"
                    "vertexnormal -2 -2 0 0 0 0\nvertexnormal 2 -2 0 0 0 0\n"
                    "vertexnormal 0 2 0 0 0 0\nvertexnormal 0 0 1 0 0 1\n"
                    "vertexnormal 1 0 1 0 0 -1\nvertexnormal 0 1 1 0 0 1\n"
                    "trinormal 0 1 2\ntrinormal 3 4 5\n")},
        Case{"shininess_zero_at_grazing_angles",
             framed("point 0 0 0.001 1 1 1\ndiffuse 1 1 1\nspecular 1 1 1\nshininess 0\n" + kQuad,
                    "camera 0 -10 0.01 0 0 0 0 0 1 40")},
        Case{"point_light_exactly_on_the_surface",
             framed("attenuation 0 0 1\npoint 0 0 0 1 1 1\ndiffuse 1 1 1\nspecular 1 1 1\n"
                    "shininess 5\n" +
                    kQuad)},
        Case{"light_inside_a_sphere",
             framed("attenuation 0 0 1\npoint 0 0 0 1 1 1\ndiffuse 1 0 0\nsphere 0 0 0 1\n")},
        Case{"light_behind_a_back_face_seen_head_on",
             // The view and light directions are opposite at the centre: L + V = 0.
             framed("point 0 0 5 1 1 1\ndiffuse 1 1 1\nspecular 1 1 1\nshininess 20\n" + kQuad,
                    "camera 0 0 -5 0 0 0 0 1 0 40")},
        Case{"huge_lights_between_parallel_mirrors",
             // 1e38 light, reflected up to 64 times between two perfect mirrors.
             "size 32 24\ncamera 0 0 0.5 0 0 -1 0 1 0 60\nmaxdepth 64\npoint 0 0 0 1e38 1e38 "
             "1e38\nattenuation 1e-30 0 0\nambient 1e38 1e38 1e38\nspecular 1 0 1e38\n"
             "diffuse 1e38 0 0\nshininess 1\n" +
                 std::string("pushTransform\ntranslate 0 0 -1\n") + kQuad +
                 "popTransform\npushTransform\ntranslate 0 0 1\n" + "tri 0 2 1\ntri 0 3 2\n" +
                 "popTransform\n"},
        Case{"scene_a_million_units_from_the_origin",
             framed("pushTransform\ntranslate 1e6 1e6 1e6\npoint 1 1 3 1 1 1\ndiffuse 1 1 1\n"
                    "specular 0.5 0.5 0.5\nshininess 30\nsphere 0 0 0 1\n" +
                        kQuad + "popTransform\n",
                    "camera 1000000 1000000 1000005 1e6 1e6 1e6 0 1 0 40")},
        Case{"scene_a_millionth_of_a_unit_across",
             framed("pushTransform\nscale 1e-6 1e-6 1e-6\npoint 1 1 3 1 1 1\ndiffuse 1 1 1\n"
                    "specular 0.5 0.5 0.5\nshininess 30\nsphere 0 0 0 1\n" +
                        kQuad + "popTransform\n",
                    "camera 0 0 5e-6 0 0 0 0 1 0 40")}),
    [](const auto& p) { return std::string(p.param.name); });

/// One of each new shape, a mirror among them, lit by a point and a directional light, on a
/// plane: about two units across around the origin.
const std::string kShapes =
    "point 1 3 3 1 1 1\ndirectional 0 1 1 0.3 0.3 0.3\nambient 0.1 0.1 0.1\n"
    "diffuse 0.8 0.6 0.4\nspecular 0.3 0.3 0.3\nshininess 20\nplane 0 -1 0 0 1 0\n"
    "box -1.5 -1 -0.5 -0.8 -0.3 0.5\ncylinder -0.4 -1 0 -0.4 0 0 0.3\n"
    "specular 0.9 0.9 0.9\ncone 0.4 -1 0 0.4 0.4 0 0 0\nspecular 0.3 0.3 0.3\n"
    "pushTransform\nrotate 1 1 0 30\nscale 1 0.5 2\ndisk 1.2 -0.5 0 0 0 1 0.3\n"
    "popTransform\nvertex -1 0.3 -0.5\nvertex 1 0.3 -0.5\nvertex 1 1 -0.5\n"
    "vertex 0 0.6 -0.5\nvertex -1 1 -0.5\npolygon 0 1 2 3 4\n";

INSTANTIATE_TEST_SUITE_P(
    Shapes, FinitePixels,
    testing::Values(
        Case{"shapes_at_unit_scale", framed(kShapes)},
        Case{"shapes_a_million_units_from_the_origin",
             framed("pushTransform\ntranslate 1e6 1e6 1e6\n" + kShapes + "popTransform\n",
                    "camera 1000000 1000000 1000005 1e6 1e6 1e6 0 1 0 40")},
        Case{"shapes_a_million_times_larger",
             framed("pushTransform\nscale 1e6 1e6 1e6\n" + kShapes + "popTransform\n",
                    "camera 0 0 5e6 0 0 0 0 1 0 40")},
        Case{"shapes_a_ten_thousandth_of_the_size",
             framed("pushTransform\nscale 1e-4 1e-4 1e-4\n" + kShapes + "popTransform\n",
                    "camera 0 0 5e-4 0 0 0 0 1 0 40")},
        Case{"camera_inside_a_box_a_cylinder_and_a_cone",
             framed("point 0 0 0.5 1 1 1\ndiffuse 1 1 1\nspecular 0.5 0.5 0.5\n"
                    "box -3 -3 -3 3 3 8\ncylinder 0 0 -2 0 0 7 2\n"
                    "cone 0 0 -1 1.5 0 0 6.5 0.5\n")},
        Case{"light_on_a_box_face_and_inside_a_cylinder",
             framed("attenuation 0 0 1\npoint 0 0 1 1 1 1\ndiffuse 1 1 1\n"
                    "box -1 -1 0 1 1 1\npoint 0 0 0.5 1 1 1\n"
                    "cylinder 3 0 0 3 0 1 0.5\n")}),
    [](const auto& p) { return std::string(p.param.name); });

/// Renders `shape`, a face of which (a box side, a cap, a disk, a polygon, a plane) covers the
/// middle of the image squarely, lit by a directional light from the camera, at `scale` times
/// its unit size. Every middle pixel must get the full diffuse term: a darker one means the
/// surface shadowed itself (acne). Returns the number of such pixels.
int faceAcnePixels(const std::string& shape, double scale) {
    const int w = 48, h = 36;
    char text[1024];
    std::snprintf(text, sizeof text,
                  "size %d %d\ncamera 0 0 %.17g 0 0 0 0 1 0 30\ndirectional 0 0 1 1 1 1\n"
                  "ambient 0.1 0.1 0.1\ndiffuse 0.5 0.5 0.5\npushTransform\nscale %.17g %.17g "
                  "%.17g\nvertex -1 -1 0\nvertex 1 -1 0\nvertex 2 0 0\nvertex 1 1 0\n"
                  "vertex -1 1 0\n%s\npopTransform\n",
                  w, h, 4 * scale, scale, scale, scale, shape.c_str());
    std::vector<Diagnostic> warnings;
    auto scene = parseCourseScene(text, "face.test", warnings);
    scene->prepare();
    RenderOptions o;
    o.threads = 2;
    Film f = render(*scene, o).film;
    int acne = 0;
    for (int y = h / 3; y < 2 * h / 3; ++y)
        for (int x = w / 3; x < 2 * w / 3; ++x) acne += std::abs(f.at(x, y).x - 0.6) > 1e-9;
    return acne;
}

TEST(Acne, NoneOnShapeFacesAtAnyScale) {
    for (double scale : {1e-4, 1.0, 1e5})
        for (const char* shape :
             {"box -1 -1 -1 1 1 0", "cylinder 0 0 -1 0 0 0 1.5", "cone 0 0 -2 2 0 0 0 1",
              "disk 0 0 0 0 0 1 1", "plane 0 0 0 0 0 1", "polygon 0 1 2 3 4"})
            EXPECT_EQ(faceAcnePixels(shape, scale), 0) << shape << " at scale " << scale;
}

/// Renders a lit sphere of radius `r` at the origin, seen from 5r away with a point light
/// beside the camera, and counts "acne": pixels that see the sphere where the light hits the
/// surface squarely (N.L > 0.2, computed exactly here) but come out no brighter than ambient.
int acnePixels(double r) {
    const int w = 96, h = 72;
    const double camZ = 5 * r, lightX = 3 * r, lightZ = 5 * r;
    char text[512];
    std::snprintf(text, sizeof text,
                  "size %d %d\ncamera 0 0 %.17g 0 0 0 0 1 0 40\npoint %.17g 0 %.17g 1 1 1\n"
                  "ambient 0.1 0.1 0.1\ndiffuse 0.8 0.8 0.8\nsphere 0 0 0 %.17g\n",
                  w, h, camZ, lightX, lightZ, r);
    std::vector<Diagnostic> warnings;
    auto scene = parseCourseScene(text, "acne.test", warnings);
    scene->prepare();
    Film f = render(*scene, RenderOptions{}).film;
    Camera camera(*scene->camera, w, h);
    int acne = 0, lit = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            Ray ray = camera.generateRay(x + 0.5, y + 0.5);
            // Exact hit in double: |o + t d| = r.
            double b = dot(ray.origin, ray.dir), c = dot(ray.origin, ray.origin) - r * r;
            double disc = b * b - c;
            if (disc < 0) continue;
            Vec3 p = ray.at(-b - std::sqrt(disc));
            Vec3 n = p / r, l = normalize(Vec3(lightX, 0, lightZ) - p);
            if (dot(n, l) < 0.2) continue;
            ++lit;
            acne += f.at(x, y).x <= 0.1 + 1e-9;  // only the ambient term: the point shadowed itself
        }
    EXPECT_GT(lit, 500) << "the test must look at many lit pixels (r = " << r << ")";
    return acne;
}

TEST(Acne, NoneOnATinySphere) { EXPECT_EQ(acnePixels(1e-3), 0); }
TEST(Acne, NoneOnAUnitSphere) { EXPECT_EQ(acnePixels(1), 0); }
TEST(Acne, NoneOnAHugeSphere) { EXPECT_EQ(acnePixels(1e5), 0); }

}  // namespace
}  // namespace glint
