// The loader's commands for Glint's extensions beyond Whitted: materials (transmission, ior,
// roughness), area lights, sampling (spp, filter, lightsamples), the thin lens and the integrator.

#include <gtest/gtest.h>

#include "glint/io/course/course_loader.h"
#include "unit/io/course/course_test_support.h"
#include "unit/test_support.h"

namespace glint {
namespace {

using namespace test;  // NOLINT: the loader test helpers

TEST(CourseExtensions, DefaultsLeaveTheCourseModelUnchanged) {
    auto s = parseOk("sphere 0 0 0 1\n");
    const Material& m = s->materials.at(0);
    EXPECT_EQ(m.transmission, Vec3(0));
    EXPECT_FALSE(m.transmissive());
    EXPECT_EQ(m.roughness, 0);
    EXPECT_EQ(s->spp, 0);
    EXPECT_EQ(s->lightSamples, 0);
    EXPECT_EQ(s->filter, FilterSpec{});
    EXPECT_EQ(s->camera->apertureRadius, 0);
}

TEST(CourseExtensions, TransmissionIorAndRoughnessAreMaterialState) {
    auto s = parseOk(
        "transmission 0.9 0.8 0.7\nior 1.33\nroughness 0.25\nsphere 0 0 0 1\n"
        "transmission 0 0 0\nroughness 0\nsphere 3 0 0 1\n");
    ASSERT_EQ(s->materials.size(), 2u);
    expectNear(s->materials[0].transmission, {0.9, 0.8, 0.7});
    EXPECT_EQ(s->materials[0].ior, 1.33);
    EXPECT_EQ(s->materials[0].roughness, 0.25);
    EXPECT_FALSE(s->materials[1].transmissive());
    EXPECT_EQ(s->materials[1].ior, 1.33);  // state persists until changed
}

TEST(CourseExtensions, MaterialErrors) {
    expectError("ior 0\n", 1, 5, "ior must be positive");
    expectError("ior -1.5\n", 1, 5, "ior must be positive");
    expectError("roughness 1.5\n", 1, 11, "between 0 and 1");
    expectError("roughness -0.1\n", 1, 11, "between 0 and 1");
    expectError("transmission 1 1\n", 1, 1, "transmission expects 3 arguments");
}

TEST(CourseExtensions, QuadLightIsALightAndAnEmittingSurface) {
    auto s = parseOk("translate 0 5 0\nquadLight -1 0 -1 2 0 0 0 0 2 4 4 4\n");
    ASSERT_EQ(s->lights.size(), 1u);
    const LightSpec& l = s->lights[0];
    EXPECT_EQ(l.kind, LightSpec::Kind::Quad);
    expectNear(l.position, {-1, 5, -1});
    expectNear(l.edge1, {2, 0, 0});
    expectNear(l.edge2, {0, 0, 2});
    EXPECT_NEAR(l.quadArea(), 4, 1e-12);
    expectNear(normalize(cross(l.edge1, l.edge2)), {0, -1, 0});  // emits downwards
    EXPECT_EQ(s->primitives.triangleCount(), 2u);
    // Seen from below: the emitting face, radiance 4; from above: the back, black.
    auto below = shoot(*s, {0.3, 0, 0.2}, {0, 1, 0});
    ASSERT_TRUE(below);
    const Material& m = s->materials.at(below->material);
    EXPECT_EQ(m.emission, Vec3(4));
    EXPECT_TRUE(m.frontEmissionOnly);
    EXPECT_EQ(m.ambient, Vec3(0));
}

TEST(CourseExtensions, QuadLightDoesNotDisturbTheCurrentMaterial) {
    auto s = parseOk(
        "diffuse 1 0 0\nsphere 0 0 0 1\nquadLight 0 5 0 1 0 0 0 0 1 1 1 1\n"
        "sphere 3 0 0 1\n");
    auto si = shoot(*s, {3, 0, 10}, {0, 0, -1});
    ASSERT_TRUE(si);
    EXPECT_EQ(s->materials.at(si->material).diffuse, Vec3(1, 0, 0));
    EXPECT_EQ(s->materials.at(si->material).emission, Vec3(0));
}

TEST(CourseExtensions, QuadLightErrors) {
    expectError("quadLight 0 0 0 1 0 0 2 0 0 1 1 1\n", 1, 17, "zero or parallel");
    expectError("quadLight 0 0 0 0 0 0 0 0 1 1 1 1\n", 1, 17, "zero or parallel");
    expectError("quadLight 0 0 0 1 0 0 0 0 1 1 1\n", 1, 1, "quadLight expects 12 arguments");
    expectError("quadlight 0 0 0 1 0 0 0 0 1 1 1 1\n", 1, 1, "did you mean 'quadLight'");
}

TEST(CourseExtensions, SamplingSettings) {
    auto s = parseOk("spp 16\nlightsamples 3\nfilter gaussian\n");
    EXPECT_EQ(s->spp, 16);
    EXPECT_EQ(s->lightSamples, 3);
    EXPECT_EQ(s->filter.kind, FilterSpec::Kind::Gaussian);
    EXPECT_EQ(s->filter.radius, 1.5);
    auto box = parseOk("filter box 1\n");
    EXPECT_EQ(box->filter.kind, FilterSpec::Kind::Box);
    EXPECT_EQ(box->filter.radius, 1);
}

TEST(CourseExtensions, SamplingErrors) {
    expectError("spp 0\n", 1, 5, "out of range (1 to 65536)");
    expectError("spp 2.5\n", 1, 5, "expected an integer");
    expectError("lightsamples 65\n", 1, 14, "out of range (1 to 64)");
    expectError("filter mitchell\n", 1, 8, "unknown filter 'mitchell' (box or gaussian)");
    expectError("filter gaussian 0.1\n", 1, 17, "0.5 to 4 pixels");
    expectError("filter\n", 1, 1, "filter expects 1 or 2 arguments");
}

TEST(CourseExtensions, IntegratorNamesOneGlintHas) {
    EXPECT_EQ(parseOk("sphere 0 0 0 1\n")->integrator, "whitted");
    EXPECT_EQ(parseOk("integrator whitted\n")->integrator, "whitted");
    expectError("integrator photon-mapping\n", 1, 12,
                "unknown integrator 'photon-mapping' (Glint has whitted");
    expectError("integrator\n", 1, 1, "integrator expects 1 argument (name), got 0");
}

TEST(CourseExtensions, LensSetsApertureAndFocusWhereverItAppears) {
    auto s = parseOk("lens 0.1 7.5\n");
    EXPECT_EQ(s->camera->apertureRadius, 0.1);
    EXPECT_EQ(s->camera->focusDistance, 7.5);
    auto dflt = parseOk("lens 0.2\n");
    EXPECT_EQ(dflt->camera->apertureRadius, 0.2);
    EXPECT_EQ(dflt->camera->focusDistance, 0);  // the camera's eye-to-center distance
    expectError("lens -1\n", 1, 6, "must not be negative");
    expectError("lens 0.1 0\n", 1, 10, "focus distance must be positive");
}

}  // namespace
}  // namespace glint
