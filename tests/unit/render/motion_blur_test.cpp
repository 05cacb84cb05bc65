// Motion blur (math/motion.h, the scene files' `motion`, docs/animation.md): transforms keyed
// over the shutter and interpolated as pbrt's AnimatedTransform does; each camera sample at its
// own time; a moving sphere blurred equals the average of still frames at evenly spaced times;
// a shutter of zero length, and a still scene with a shutter, give the still frame exactly.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "glint/io/course/course_loader.h"
#include "glint/math/motion.h"
#include "glint/render/renderer.h"
#include "glint/scene/scene.h"

namespace glint {
namespace {

Transform from(const Mat4& m) { return *Transform::fromMatrix(m); }

void expectNear(const Vec3& a, const Vec3& b, double tolerance = 1e-9) {
    EXPECT_NEAR(a.x, b.x, tolerance);
    EXPECT_NEAR(a.y, b.y, tolerance);
    EXPECT_NEAR(a.z, b.z, tolerance);
}

TEST(MotionPath, KeysAreHitExactlyAndRigidTurnsKeepTheirShape) {
    // A quarter turn about z at (3, 0, 0), and a move of 2 along y, over the shutter.
    const Mat4 at = Mat4::translate(3, 0, 0);
    const MotionPath path({from(at), from(Mat4::translate(0, 2, 0) * at *
                                          Mat4::rotate(0, 0, 1, 90) * Mat4::scale(2, 2, 2))});
    EXPECT_TRUE(path.moves());
    expectNear(path.at(0).point({1, 0, 0}), {4, 0, 0});
    expectNear(path.at(1).point({1, 0, 0}), {3, 4, 0});
    // Halfway: an eighth of a turn about the object's origin, which moved 1 along y; the
    // scale halfway too (1.5). The origin does not wander off the line.
    const Transform half = path.at(0.5f);
    expectNear(half.point({0, 0, 0}), {3, 1, 0});
    const double c = std::cos(std::numbers::pi / 4) * 1.5;
    expectNear(half.point({1, 0, 0}), {3 + c, 1 + c, 0});
    // Before and after the shutter: its ends.
    expectNear(path.at(-1).point({1, 0, 0}), {4, 0, 0});
    expectNear(path.at(2).point({1, 0, 0}), {3, 4, 0});
    // delta takes what the first key placed to where it is now.
    expectNear(path.delta(1).point({4, 0, 0}), {3, 4, 0});
    expectNear(path.delta(0).point({4, 0, 0}), {4, 0, 0});
}

TEST(MotionPath, MirroringKeysAreKeptAtTheKeys) {
    const std::vector<Transform> keys = {from(Mat4::scale(-1, 1, 1)),
                                         from(Mat4::rotate(0, 1, 0, 40) * Mat4::scale(-2, 1, 1)),
                                         from(Mat4::translate(1, 1, 1) * Mat4::scale(-1, 3, 1))};
    const MotionPath path(keys);
    for (size_t k = 0; k < keys.size(); ++k) {
        const float u = static_cast<float>(k) / 2;
        for (const Vec3& p : {Vec3(1, 2, 3), Vec3(-1, 0.5, 2)})
            expectNear(path.at(u).point(p), keys[k].point(p), 1e-9);
        EXPECT_LT(path.at(u).determinant(), 0);
    }
}

TEST(MotionPath, TheSweptBoundsHoldTheBoxAtEveryTime) {
    const MotionPath path({from(Mat4::identity()), from(Mat4::rotate(1, 1, 0, 170)),
                           from(Mat4::translate(5, 0, 0) * Mat4::rotate(0, 0, 1, 300))});
    Bounds3f box;
    box.extend(Vec3f(-1, -0.5f, 0));
    box.extend(Vec3f(2, 0.5f, 0.25f));
    const Bounds3f swept = path.sweep(box);
    for (int i = 0; i <= 1000; ++i) {
        const Transform d = path.delta(static_cast<float>(i) / 1000);
        for (int corner = 0; corner < 8; ++corner) {
            const Vec3 p =
                d.point(Vec3(corner & 1 ? box.hi.x : box.lo.x, corner & 2 ? box.hi.y : box.lo.y,
                             corner & 4 ? box.hi.z : box.lo.z));
            for (int a = 0; a < 3; ++a) {
                EXPECT_GE(p[a], swept.lo[a]) << "time " << i << " corner " << corner;
                EXPECT_LE(p[a], swept.hi[a]) << "time " << i << " corner " << corner;
            }
        }
    }
    // A still path sweeps nothing more.
    const MotionPath still({from(Mat4::translate(1, 0, 0)), from(Mat4::translate(1, 0, 0))});
    EXPECT_FALSE(still.moves());
    EXPECT_EQ(still.sweep(box).lo, box.lo);
    EXPECT_EQ(still.sweep(box).hi, box.hi);
}

/// A red sphere, moved by `motion` (a scene-file `motion` line, or none), in front of a grey
/// wall, lit head-on, rendered with the Whitted integrator (deterministic but for the time).
std::string ballScene(const std::string& motion, double x = -1) {
    return "size 48 24\ncamera 0 0 6 0 0 0 0 1 0 30\nmaxdepth 1\n"
           "directional 0 0 1 1 1 1\nambient 0 0 0\n"
           "diffuse 0.5 0.5 0.5\nvertex -9 -9 -1\nvertex 9 -9 -1\nvertex 9 9 -1\n"
           "vertex -9 9 -1\ntri 0 1 2\ntri 0 2 3\n"
           "pushTransform\n" +
           motion + "\ndiffuse 0.9 0.1 0.1\nsphere " + std::to_string(x) +
           " 0 0 0.6\npopTransform\n";
}

Film renderScene(const std::string& text, const ModelTime& time = {}, int spp = 16,
                 int threads = 2) {
    std::vector<Diagnostic> warnings;
    CourseOptions options;
    options.time = time;
    auto scene = parseCourseScene(text, "motion.test", warnings, options);
    scene->prepare();
    RenderOptions o;
    o.threads = threads;
    o.spp = spp;
    o.seed = 7;
    return render(*scene, o).film;
}

ModelTime shutter(double open, double close, double seconds = 0) {
    ModelTime t;
    t.seconds = seconds;
    t.shutterOpen = open;
    t.shutterClose = close;
    return t;
}

TEST(MotionBlur, ASphereMovingAcrossTheFrameEqualsTheAverageOfStillFrames) {
    // 2 units per second for one second: from x = -1 to x = 1.
    const std::string moving = ballScene("motion 2 0 0");
    const Film blurred = renderScene(moving, shutter(0, 1), 256);
    // The average of still frames at 64 evenly spaced times (midpoints of 64 strata), 16
    // samples per pixel each.
    constexpr int kStills = 64;
    std::vector<Vec3> average(static_cast<size_t>(blurred.width() * blurred.height()));
    for (int i = 0; i < kStills; ++i) {
        ModelTime t;
        t.seconds = (i + 0.5) / kStills;
        const Film still = renderScene(moving, t);
        for (int y = 0; y < still.height(); ++y)
            for (int x = 0; x < still.width(); ++x)
                average[static_cast<size_t>(y * still.width() + x)] +=
                    still.at(x, y) * (1.0 / kStills);
    }
    // Compared in 4 x 4 blocks: each block's mean, within a few times the noise of 256 random
    // times per pixel (a pixel that the sphere's edge crosses varies by up to ~0.5).
    double worst = 0, sumBlurred = 0, sumAverage = 0;
    for (int by = 0; by < blurred.height(); by += 4)
        for (int bx = 0; bx < blurred.width(); bx += 4) {
            Vec3 a(0), b(0);
            for (int y = by; y < by + 4; ++y)
                for (int x = bx; x < bx + 4; ++x) {
                    a += blurred.at(x, y) / 16.0;
                    b += average[static_cast<size_t>(y * blurred.width() + x)] / 16.0;
                }
            worst = std::max({worst, std::abs(a.x - b.x), std::abs(a.y - b.y)});
            sumBlurred += a.x;
            sumAverage += b.x;
        }
    EXPECT_LT(worst, 0.04);
    EXPECT_NEAR(sumBlurred / sumAverage, 1, 0.01);
    // The blur is there: it differs from the still frame at its middle by much more.
    ModelTime middle;
    middle.seconds = 0.5;
    const Film still = renderScene(moving, middle);
    double differs = 0;
    for (int x = 0; x < still.width(); ++x)
        differs = std::max(differs, std::abs(still.at(x, 12).x - blurred.at(x, 12).x));
    EXPECT_GT(differs, 0.2);
}

TEST(MotionBlur, AShutterOfZeroLengthGivesTheStillFrameExactly) {
    const std::string moving = ballScene("motion 2 0 0");
    ModelTime at;
    at.seconds = 0.25;
    const Film still = renderScene(moving, at);
    const Film zero = renderScene(moving, shutter(0, 0, 0.25));
    ASSERT_EQ(still.width(), zero.width());
    for (int y = 0; y < still.height(); ++y)
        for (int x = 0; x < still.width(); ++x) ASSERT_EQ(still.at(x, y), zero.at(x, y));
    // And the still frame at 0.25 s is the sphere moved there: 0.5 to the right of x = -1.
    const Film placed = renderScene(ballScene("", -0.5));
    for (int y = 0; y < still.height(); ++y)
        for (int x = 0; x < still.width(); ++x)
            ASSERT_NEAR(still.at(x, y).x, placed.at(x, y).x, 1e-6);
}

TEST(MotionBlur, AStillSceneWithAShutterGivesTheStillFrameExactly) {
    const std::string still = ballScene("");
    const Film a = renderScene(still), b = renderScene(still, shutter(-0.5, 0.5));
    for (int y = 0; y < a.height(); ++y)
        for (int x = 0; x < a.width(); ++x) ASSERT_EQ(a.at(x, y), b.at(x, y));
}

TEST(MotionBlur, TheImageDoesNotDependOnTheThreadCount) {
    const std::string moving = ballScene("motion 2 0 0 0 1 0 45");
    const Film one = renderScene(moving, shutter(0, 1), 16, 1);
    const Film four = renderScene(moving, shutter(0, 1), 16, 4);
    for (int y = 0; y < one.height(); ++y)
        for (int x = 0; x < one.width(); ++x) ASSERT_EQ(one.at(x, y), four.at(x, y));
}

TEST(MotionBlur, MovingShapesAreSearchedWhereTheyAreAtTheThreadsTime) {
    std::vector<Diagnostic> warnings;
    CourseOptions options;
    options.time = shutter(0, 1);
    auto scene = parseCourseScene(
        "size 8 8\ncamera 0 0 6 0 0 0 0 1 0 30\npushTransform\nmotion 4 0 0\n"
        "sphere -2 0 0 0.5\nbox -2.25 2 -0.25 -1.75 2.5 0.25\npopTransform\n",
        "m.test", warnings, options);
    scene->prepare();
    ASSERT_TRUE(scene->moves());
    const Ray down{{-2, 0, 6}, {0, 0, -1}, 0, kInfinity},
        right{{2, 0, 6}, {0, 0, -1}, 0, kInfinity};
    const Ray box{{2, 2.25, 6}, {0, 0, -1}, 0, kInfinity};
    Hit hit;
    setShutterTime(0);
    ASSERT_TRUE(scene->intersect(down, hit));
    EXPECT_NEAR(scene->primitives.interaction(down, hit).p.z, 0.5, 1e-6);
    hit = {};
    EXPECT_FALSE(scene->intersect(right, hit));
    EXPECT_FALSE(scene->occluded(box));
    setShutterTime(1);
    hit = {};
    EXPECT_FALSE(scene->intersect(down, hit));
    hit = {};
    ASSERT_TRUE(scene->intersect(right, hit));
    const SurfaceInteraction si = scene->primitives.interaction(right, hit);
    EXPECT_NEAR(si.p.x, 2, 1e-6);
    EXPECT_NEAR(si.n.z, 1, 1e-6);
    EXPECT_TRUE(scene->occluded(box));
    setShutterTime(0);
}

}  // namespace
}  // namespace glint
