// The integrator's extensions beyond Whitted, end to end through the scene format: refraction
// with Fresnel weighting, transmissive shadows, antialiasing and its filters, determinism with
// random sampling (lens, area lights, glossy rays) whatever the thread count.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "glint/io/course/course_loader.h"
#include "glint/render/film/filter.h"
#include "glint/render/renderer.h"

namespace glint {
namespace {

std::unique_ptr<Scene> load(const std::string& text) {
    std::vector<Diagnostic> warnings;
    auto scene = parseCourseScene(text, "ext.test", warnings);
    scene->prepare();
    return scene;
}

Film renderText(const std::string& text, int spp = 1, int threads = 2, uint64_t seed = 0) {
    auto scene = load(text);
    RenderOptions o;
    o.threads = threads;
    o.spp = spp;
    o.seed = seed;
    return render(*scene, o).film;
}

double maxDifference(const Film& a, const Film& b) {
    double d = 0;
    for (int y = 0; y < a.height(); ++y)
        for (int x = 0; x < a.width(); ++x)
            d = std::max(d, maxComponent(abs(a.at(x, y) - b.at(x, y))));
    return d;
}

const std::string kFloorAndLight =
    "size 40 30\ncamera 0 6 6 0 0 0 0 1 0 45\n"
    "ambient 0 0 0\ndiffuse 0.8 0.8 0.8\n"
    "vertex -5 0 -5\nvertex 5 0 -5\nvertex 5 0 5\nvertex -5 0 5\ntri 0 2 1\ntri 0 3 2\n"
    "point 0 5 0 1 1 1\n";

TEST(Refraction, GlassOfIndexOneIsInvisibleAndCastsNoShadow) {
    std::string glass =
        "ambient 0 0 0\ndiffuse 0 0 0\ntransmission 1 1 1\nior 1\nsphere 0 1.5 0 0.8\n";
    Film without = renderText(kFloorAndLight);
    Film with = renderText(kFloorAndLight + glass);
    EXPECT_LT(maxDifference(without, with), 1e-9);
}

TEST(Refraction, ClearGlassLosesNoEnergyInAUniformSurrounding) {
    // Reflected plus transmitted weights are 1 at every interface: in a uniform white
    // surrounding every ray returns white, up to the paths cut at maxdepth and the branches
    // cut below 1e-3. Checked for a sphere, an ellipsoid under a rotation, a closed mesh, a
    // box, a cylinder and a cone.
    // (Total internal reflection traps some rays in the ellipsoid for over 12 bounces: at
    // maxdepth 12 one pixel keeps only 0.19; the full depth is needed.)
    std::string common =
        "size 41 41\ncamera 0 0 4 0 0 0 0 1 0 40\nmaxdepth 64\nbackground 1 1 1\n"
        "ambient 0 0 0\ntransmission 1 1 1\nior 1.5\n";
    std::string shapes[] = {
        "sphere 0 0 0 1\n", "rotate 1 1 0 30\nscale 1.2 0.7 0.9\nsphere 0 0 0 1\n",
        // An octahedron, faces wound counter-clockwise seen from outside.
        "vertex 1 0 0\nvertex -1 0 0\nvertex 0 1 0\nvertex 0 -1 0\nvertex 0 0 1\nvertex 0 0 -1\n"
        "tri 0 2 4\ntri 2 1 4\ntri 1 3 4\ntri 3 0 4\ntri 2 0 5\ntri 1 2 5\ntri 3 1 5\n"
        "tri 0 3 5\n",
        // The lecture's other solids, under rotations: inside hits and outward normals.
        "rotate 1 2 0 25\nbox -0.8 -0.6 -0.7 0.8 0.6 0.7\n",
        "rotate 1 0 0 60\ncylinder 0 -0.8 0 0 0.8 0 0.7\n",
        // At index 1.5 total internal reflection between a frustum's side and base keeps one
        // ray inside for about 70 bounces (traced: it is physics, not a leak), so the cone is
        // checked at 1.2, where light escapes well within the depth.
        "ior 1.2\nrotate 0 0 1 20\ncone 0 -0.8 0 0.8 0 0.8 0 0.3\n"};
    for (const std::string& shape : shapes) {
        Film f = renderText(common + shape);
        double lowest = 1;
        for (int y = 0; y < f.height(); ++y)
            for (int x = 0; x < f.width(); ++x) lowest = std::min(lowest, f.at(x, y).x);
        EXPECT_GT(lowest, 0.99) << shape;
    }
}

TEST(Refraction, RaysEnterAndLeaveASphereBySnellsLaw) {
    // A ray at height h = 0.5 along +x through the unit sphere of index 1.5 turns by
    // 2 (asin(h) - asin(h / 1.5)) = 21.06 degrees towards the axis in all, leaving from the
    // point found by the chord inside. A small emitter placed where that ray crosses x = 6
    // is seen through the glass with weight (1 - F)^2; anywhere else there is nothing.
    const double h = 0.5, n = 1.5;
    double ti = std::asin(h), tt = std::asin(h / n);
    double inside = ti - tt;            // below horizontal, radians
    double ex = -std::cos(ti), ey = h;  // entry point
    double chord = 2 * std::cos(tt);    // chord length in a unit sphere
    double xx = ex + chord * std::cos(inside), xy = ey - chord * std::sin(inside);  // exit
    double out = 2 * inside;
    double hitY = xy - (6 - xx) * std::tan(out);
    auto scene = [&](double targetY) {
        char target[512];
        std::snprintf(target, sizeof target,
                      "vertex 0 -0.03 -0.03\nvertex 0 0.03 -0.03\nvertex 0 0.03 0.03\n"
                      "vertex 0 -0.03 0.03\npushTransform\ntranslate 6 %.17g 0\n"
                      "transmission 0 0 0\nemission 1 1 1\ntri 0 1 2\ntri 0 2 3\npopTransform\n",
                      targetY);
        // A 1 x 1 image with a tiny field of view: its one ray is the one above.
        return std::string("size 1 1\ncamera -5 0.5 0 0 0.5 0 0 1 0 0.001\nmaxdepth 4\n") +
               "ambient 0 0 0\ntransmission 1 1 1\nior 1.5\nsphere 0 0 0 1\n" + target;
    };
    double cosOut = std::cos(ti);
    double f1 = 0.5 * (std::pow((cosOut - n * std::cos(tt)) / (cosOut + n * std::cos(tt)), 2) +
                       std::pow((n * cosOut - std::cos(tt)) / (n * cosOut + std::cos(tt)), 2));
    double expected = (1 - f1) * (1 - f1);  // the same Fresnel factor at entry and exit
    Film seen = renderText(scene(hitY));
    EXPECT_NEAR(seen.at(0, 0).x, expected, 1e-6);
    Film missed = renderText(scene(hitY + 0.2));
    EXPECT_EQ(missed.at(0, 0).x, 0);
}

TEST(Refraction, ShadowsThroughGlassAreFilteredByTransmissionAtEachSurface) {
    // A slab of transmission 0.5 and index 1 (no Fresnel loss) between the light and the
    // floor: the light crosses two surfaces, 0.5 x 0.5.
    std::string slab =
        "ambient 0 0 0\ndiffuse 0 0 0\ntransmission 0.5 0.5 0.5\nior 1\n"
        "vertex -5 2 -5\nvertex 5 2 -5\nvertex 5 2 5\nvertex -5 2 5\n"
        "vertex -5 1.5 -5\nvertex 5 1.5 -5\nvertex 5 1.5 5\nvertex -5 1.5 5\n"
        "tri 4 6 5\ntri 4 7 6\ntri 8 9 10\ntri 8 10 11\n";
    std::string camera = "size 1 1\ncamera 0 1 0 0 0 0 0 0 -1 1\n";  // under the slab
    std::string base = kFloorAndLight.substr(kFloorAndLight.find("ambient"));
    Film open = renderText(camera + base);
    Film shaded = renderText(camera + base + slab);
    ASSERT_GT(open.at(0, 0).x, 0.1);
    EXPECT_NEAR(shaded.at(0, 0).x, 0.25 * open.at(0, 0).x, 1e-9);
}

/// A 1 x 1 image of the plane z = 0 seen head-on: the pixel spans x in [-1, 1]. Everything at
/// x > edge emits white, the rest is black.
std::string halfPlane(double edge, const std::string& extra = "") {
    char text[512];
    std::snprintf(text, sizeof text,
                  "size 1 1\ncamera 0 0 1 0 0 0 0 1 0 90\n%s"
                  "ambient 0 0 0\nemission 1 1 1\n"
                  "vertex %.17g -50 0\nvertex 50 -50 0\nvertex 50 50 0\nvertex %.17g 50 0\n"
                  "tri 0 1 2\ntri 0 2 3\n",
                  extra.c_str(), edge, edge);
    return text;
}

TEST(Antialiasing, EdgePixelsConvergeToTheCoveredFraction) {
    for (double edge : {-0.5, 0.2, 0.4, 0.9}) {
        double covered = (1 - edge) / 2;
        // 4096 = 64 x 64 strata: the column the edge crosses errs by at most 1/64 of its
        // share, so a few thousandths at most.
        Film f = renderText(halfPlane(edge), 4096);
        std::printf("edge at %.2f: covered %.4f, pixel %.4f\n", edge, covered, f.at(0, 0).x);
        EXPECT_NEAR(f.at(0, 0).x, covered, 0.004) << "edge at " << edge;
    }
    // One sample per pixel sees only the centre.
    EXPECT_EQ(renderText(halfPlane(0.4), 1).at(0, 0).x, 0);
}

TEST(Antialiasing, GaussianFilterConvergesToTheFilterWeightedCoverage) {
    // Pixel units: the image spans 2 world units per pixel; the edge at world x = 0.4 is at
    // 0.2 pixels from the centre. The expected value is the filter's mass beyond it.
    FilterSampler g(FilterSpec{FilterSpec::Kind::Gaussian, 1.5});
    double beyond = 0, total = 0;
    for (int i = 0; i < 30000; ++i) {
        double x = -1.5 + 3 * (i + 0.5) / 30000;
        total += g.profile(x);
        if (x > 0.2) beyond += g.profile(x);
    }
    Film f = renderText(halfPlane(0.4, "filter gaussian 1.5\n"), 4096);
    std::printf("gaussian: filter-weighted coverage %.4f, pixel %.4f\n", beyond / total,
                f.at(0, 0).x);
    EXPECT_NEAR(f.at(0, 0).x, beyond / total, 0.004);
    EXPECT_LT(beyond / total, 0.40);  // unlike the box's 0.3 ... the two must differ
    EXPECT_GT(beyond / total, 0.30);
}

const std::string kEverything =
    "size 48 36\ncamera 0 3 6 0 0.5 0 0 1 0 45\nlens 0.08 6\nfilter gaussian\nspp 6\n"
    "lightsamples 2\nbackground 0.1 0.1 0.2 0.5 0.6 0.9\n"
    "ambient 0.05 0.05 0.05\ndiffuse 0.6 0.6 0.6\n"
    "vertex -5 0 -5\nvertex 5 0 -5\nvertex 5 0 5\nvertex -5 0 5\ntri 0 2 1\ntri 0 3 2\n"
    "quadLight -1 3 -1 2 0 0 0 0 2 3 3 3\n"
    "diffuse 0.1 0.1 0.1\nspecular 0.8 0.8 0.8\nroughness 0.3\nsphere -1.2 0.7 0 0.7\n"
    "specular 0 0 0\nroughness 0\ndiffuse 0 0 0\ntransmission 0.9 0.9 0.9\nior 1.5\n"
    "sphere 1.2 0.7 0 0.7\n";

TEST(Sampling, ImagesDoNotDependOnTheThreadCount) {
    auto scene = load(kEverything);
    RenderOptions o;
    o.spp = scene->spp;
    o.threads = 1;
    Film one = render(*scene, o).film;
    o.threads = 3;
    Film three = render(*scene, o).film;
    EXPECT_EQ(maxDifference(one, three), 0);
    o.seed = 5;
    Film other = render(*scene, o).film;
    EXPECT_GT(maxDifference(one, other), 0.01) << "the seed changes nothing";
}

TEST(Sampling, AreaLightsCastSoftShadows) {
    // Under a blocker, the floor goes from lit through penumbra to umbra: along a line of
    // pixels across the shadow edge, more than two distinct levels appear.
    std::string text =
        "size 64 1\ncamera 0 0.01 0 0 0 0 0 0 -1 100\nlightsamples 8\n"
        "ambient 0 0 0\ndiffuse 1 1 1\n"
        "vertex -50 0 -50\nvertex 50 0 -50\nvertex 50 0 50\nvertex -50 0 50\ntri 0 2 1\n"
        "tri 0 3 2\nquadLight -0.5 4 -0.5 1 0 0 0 0 1 1 1 1\n"
        "vertex -10 1 -10\nvertex 0 1 -10\nvertex 0 1 10\nvertex -10 1 10\ntri 4 6 5\ntri 4 7 6\n";
    Film f = renderText(text, 1);
    int levels = 0;
    double last = -1;
    for (int x = 0; x < f.width(); ++x) {
        double v = f.at(x, 0).x;
        if (std::abs(v - last) > 1e-3) ++levels, last = v;
    }
    EXPECT_GT(levels, 8);
    EXPECT_EQ(f.at(0, 0).x, 0);                 // umbra at the left
    EXPECT_GT(f.at(f.width() - 1, 0).x, 0.01);  // lit at the right
}

}  // namespace
}  // namespace glint
