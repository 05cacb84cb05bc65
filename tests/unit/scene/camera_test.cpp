#include "glint/scene/camera.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "unit/test_support.h"

namespace glint {
namespace {

using test::expectNear;

double radians(double degrees) { return degrees * std::numbers::pi / 180; }

/// The gluLookAt frame, built independently: forward, right = forward x up, true up.
struct Frame {
    Vec3 f, r, u;
    explicit Frame(const CameraSpec& s) {
        f = normalize(s.center - s.eye);
        r = normalize(cross(f, s.up));
        u = cross(r, f);
    }
    /// Unit direction that makes tangents (a, b) with the view direction, right and up.
    Vec3 dir(double a, double b) const { return normalize(f + r * a + u * b); }
};

double angle(const Vec3& a, const Vec3& b) { return std::acos(dot(a, b)); }

// An oblique camera: the view direction is on no axis.
const CameraSpec kOblique{{1, 2, 3}, {-2, 0, 7}, {0, 1, 0}, 50};

TEST(Camera, ImageCentreLooksAtTheCentrePoint) {
    for (auto [w, h] : {std::pair{640, 480}, std::pair{101, 37}, std::pair{200, 400}}) {
        Camera cam(kOblique, w, h);
        Ray ray = cam.generateRay(w / 2.0, h / 2.0);
        expectNear(ray.origin, kOblique.eye, 0);
        expectNear(ray.dir, normalize(kOblique.center - kOblique.eye));
        EXPECT_EQ(ray.tMin, 0);
        EXPECT_EQ(ray.tMax, kInfinity);
    }
}

TEST(Camera, RaysAreUnitLength) {
    Camera cam(kOblique, 64, 48);
    for (double x : {0.0, 13.5, 64.0})
        for (double y : {0.0, 7.25, 48.0}) EXPECT_NEAR(length(cam.generateRay(x, y).dir), 1, 1e-15);
}

TEST(Camera, CornersHaveTheAnglesOfTheFieldOfView) {
    // tan(fovx/2) = tan(fovy/2) * w / h, for landscape, portrait and square images.
    for (auto [w, h] : {std::pair{640, 480}, std::pair{200, 400}, std::pair{50, 50}}) {
        SCOPED_TRACE(w);
        Camera cam(kOblique, w, h);
        Frame fr(kOblique);
        double ty = std::tan(radians(kOblique.fovyDegrees / 2));
        double tx = ty * w / h;
        auto W = static_cast<double>(w), H = static_cast<double>(h);
        expectNear(cam.generateRay(0, 0).dir, fr.dir(-tx, ty));  // top left
        expectNear(cam.generateRay(W, 0).dir, fr.dir(tx, ty));   // top right
        expectNear(cam.generateRay(0, H).dir, fr.dir(-tx, -ty));
        expectNear(cam.generateRay(W, H).dir, fr.dir(tx, -ty));
        EXPECT_NEAR(angle(cam.generateRay(0, 0).dir, fr.f), std::atan(std::hypot(tx, ty)), 1e-12);
    }
}

TEST(Camera, EdgeMidpointsAreHalfTheFieldOfViewAway) {
    CameraSpec spec{{0, 0, 0}, {0, 0, -1}, {0, 1, 0}, 60};
    Camera cam(spec, 640, 480);
    Vec3 f{0, 0, -1};
    double fovy = radians(60), fovx = 2 * std::atan(std::tan(fovy / 2) * 640 / 480);
    EXPECT_NEAR(angle(cam.generateRay(320, 0).dir, f), fovy / 2, 1e-12);
    EXPECT_NEAR(angle(cam.generateRay(320, 480).dir, f), fovy / 2, 1e-12);
    EXPECT_NEAR(angle(cam.generateRay(0, 240).dir, f), fovx / 2, 1e-12);
    EXPECT_NEAR(angle(cam.generateRay(640, 240).dir, f), fovx / 2, 1e-12);
}

TEST(Camera, RowZeroIsTheTopAndColumnZeroTheLeft) {
    // Looking down -z with y up: right is +x.
    CameraSpec spec{{0, 0, 0}, {0, 0, -1}, {0, 1, 0}, 45};
    Camera cam(spec, 100, 80);
    EXPECT_GT(cam.generateRay(50, 0).dir.y, 0);
    EXPECT_LT(cam.generateRay(50, 80).dir.y, 0);
    EXPECT_LT(cam.generateRay(0, 40).dir.x, 0);
    EXPECT_GT(cam.generateRay(100, 40).dir.x, 0);
    // y grows downwards: successive rows point lower.
    EXPECT_GT(cam.generateRay(50, 10).dir.y, cam.generateRay(50, 11).dir.y);
}

TEST(Camera, UpVectorNeedNotBeOrthogonalToTheViewDirection) {
    Vec3 view = kOblique.center - kOblique.eye;
    CameraSpec tilted = kOblique;
    tilted.up = kOblique.up + view * 0.7;  // same plane as up and view: same frame
    CameraSpec scaled = kOblique;
    scaled.up = kOblique.up * 3.0;
    Camera a(kOblique, 64, 48), b(tilted, 64, 48), c(scaled, 64, 48);
    for (double x : {0.0, 20.5, 64.0})
        for (double y : {0.0, 31.5, 48.0}) {
            expectNear(b.generateRay(x, y).dir, a.generateRay(x, y).dir);
            expectNear(c.generateRay(x, y).dir, a.generateRay(x, y).dir);
        }
    // The top of the image is still towards the given up vector.
    EXPECT_GT(dot(b.generateRay(32, 0).dir, kOblique.up),
              dot(b.generateRay(32, 48).dir, kOblique.up));
}

TEST(Camera, PixelCentresAreHalfAPixelIn) {
    // In an odd-sized image the middle pixel's centre is the image centre.
    CameraSpec spec{{0, 0, 0}, {0, 0, -1}, {0, 1, 0}, 90};
    Camera cam(spec, 5, 3);
    expectNear(cam.generateRay(2 + 0.5, 1 + 0.5).dir, {0, 0, -1});
    // Pixel (0, 0)'s centre: tan(45) = 1 vertically, 5/3 horizontally over half-sizes 2.5 and
    // 1.5, at offsets -2 and +1 pixels from the centre.
    double a = -(5.0 / 3.0) * 2 / 2.5, b = 1.0 / 1.5;
    expectNear(cam.generateRay(0.5, 0.5).dir, normalize(Vec3{a, b, -1}));
}

}  // namespace
}  // namespace glint

namespace glint {
namespace {

TEST(ThinLens, AllRaysThroughAPixelMeetOnThePlaneInFocus) {
    CameraSpec spec{{0, 1, 8}, {0, 0, 0}, {0, 1, 0}, 40};
    spec.apertureRadius = 0.3;
    spec.focusDistance = 5;
    Camera lens(spec, 64, 48);
    Camera pinhole(CameraSpec{spec.eye, spec.center, spec.up, 40}, 64, 48);
    Vec3 w = normalize(spec.eye - spec.center);
    for (auto [x, y] : {std::pair{10.5, 7.25}, std::pair{32.0, 24.0}, std::pair{60.1, 40.9}}) {
        Ray p = pinhole.generateRay(x, y);
        Vec3 focus = p.at(5 / dot(p.dir, -w));
        double spread = 0;
        for (double u : {0.05, 0.5, 0.95})
            for (double v : {0.1, 0.6, 0.99}) {
                Ray r = lens.generateRay(x, y, u, v);
                EXPECT_NEAR(length(r.dir), 1, 1e-12);
                // The ray starts on the aperture disk, in the lens plane...
                Vec3 offset = r.origin - spec.eye;
                EXPECT_NEAR(dot(offset, w), 0, 1e-12);
                EXPECT_LE(length(offset), 0.3 + 1e-12);
                spread = std::max(spread, length(offset));
                // ...and passes through the pinhole ray's point on the plane in focus.
                Vec3 q = r.at(dot(focus - r.origin, r.dir));
                EXPECT_NEAR(length(q - focus), 0, 1e-9);
            }
        EXPECT_GT(spread, 0.2);  // the aperture is really used
    }
}

TEST(ThinLens, ZeroApertureIsThePinhole) {
    CameraSpec spec{{1, 2, 3}, {0, 0, 0}, {0, 1, 0}, 50};
    Camera c(spec, 20, 10);
    EXPECT_FALSE(c.hasLens());
    Ray a = c.generateRay(3.5, 4.5), b = c.generateRay(3.5, 4.5, 0.9, 0.1);
    EXPECT_EQ(a.origin, b.origin);
    EXPECT_EQ(a.dir, b.dir);
}

TEST(ThinLens, DefaultFocusIsTheDistanceFromEyeToCenter) {
    CameraSpec spec{{0, 0, 6}, {0, 0, 0}, {0, 1, 0}, 30};
    spec.apertureRadius = 0.5;
    Camera c(spec, 9, 9);
    // The centre pixel's rays all pass through the look-at point.
    for (double u : {0.1, 0.7}) {
        Ray r = c.generateRay(4.5, 4.5, u, 0.3);
        Vec3 q = r.at(dot(Vec3(0, 0, 0) - r.origin, r.dir));
        EXPECT_NEAR(length(q), 0, 1e-9);
    }
}

}  // namespace
}  // namespace glint
