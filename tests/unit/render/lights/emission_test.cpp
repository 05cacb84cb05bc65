// Every kind of light (render/lights/light.h) as light paths see it: sampleLe's rays against
// pdfLe's densities and against the flux they say they carry, and the flux into a sphere
// measured two independent ways: the mean weight of the rays sampleLe aims at it, and the
// irradiance sampleLi gives the points of its surface from outside, integrated over it. Also
// sampleLi against pdfLi for the lights that a path can hit, spot lights' cone, and how every
// light prints itself.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "glint/math/rng.h"
#include "glint/render/lights/light.h"
#include "glint/render/lights/light_sampler.h"
#include "unit/statistics.h"

namespace glint {
namespace {

constexpr double kPi = std::numbers::pi;

struct Case {
    std::string name;
    Light light;
};

/// A scene's lights with one emissive primitive or environment, kept alive with the scene.
struct SceneLights {
    std::unique_ptr<Scene> scene = std::make_unique<Scene>();
    std::unique_ptr<LightSampler> sampler;
    const Light& only() {
        scene->prepare();
        sampler = std::make_unique<LightSampler>(*scene);
        EXPECT_EQ(sampler->size(), 1u);
        return sampler->light(0);
    }
};

Material emitter(const Vec3& radiance, bool frontOnly = false) {
    Material m;
    m.emission = radiance;
    m.frontEmissionOnly = frontOnly;
    return m;
}

// The target sphere: centred at the origin, radius 1. Every light below lies outside it.
const LightLeContext kTarget{Vec3(0), 1, 40, 0};

std::vector<SceneLights>& keep() {
    static std::vector<SceneLights> scenes;
    return scenes;
}

std::vector<Case> cases() {
    std::vector<Case> c;
    c.push_back({"point", PointLight{{0.5, 3, -1}, {2, 3, 4}, {0, 0, 1}}});
    c.push_back({"spot", SpotLight{{0.3, 2.5, 0.4},
                                   normalize(Vec3(-0.1, -1, -0.2)),
                                   {5, 5, 5},
                                   {0, 0, 1},
                                   std::cos(0.2),
                                   std::cos(0.45)}});
    c.push_back({"directional", DirectionalLight{normalize(Vec3(0.3, 1, 0.2)), {1, 2, 3}}});
    c.push_back({"quad", QuadLight{{-1, 2, -0.5}, {2, 0, 0.3}, {0, 0.2, 1.5}, {1.5, 1, 0.5}}});
    {
        SceneLights& s = keep().emplace_back();
        s.scene->primitives.addTriangle({-1, 2, 0}, {1.5, 2.5, 0.5}, {0, 1.8, 1.5}, nullptr,
                                        s.scene->addMaterial(emitter({3, 2, 1})));
        c.push_back({"triangle", s.only()});
    }
    {
        SceneLights& s = keep().emplace_back();
        s.scene->primitives.addTriangle({-1, 2, 0}, {1.5, 2.5, 0.5}, {0, 1.8, 1.5}, nullptr,
                                        s.scene->addMaterial(emitter({3, 2, 1}, true)));
        c.push_back({"triangle, front only", s.only()});
    }
    {
        SceneLights& s = keep().emplace_back();
        s.scene->primitives.addSphere(Sphere{{2, 1.5, 0}, 0.5, Transform()},
                                      s.scene->addMaterial(emitter({1, 1, 2})));
        c.push_back({"sphere", s.only()});
    }
    {
        SceneLights& s = keep().emplace_back();
        const Mat4 stretched = Mat4::translate(-1.5, 2, 0.5) * Mat4::scale(0.4, 0.8, 0.5);
        s.scene->primitives.addShape(Shape{ShapeKind::Box, 1, *Transform::fromMatrix(stretched)},
                                     s.scene->addMaterial(emitter({2, 1, 1})));
        c.push_back({"box", s.only()});
    }
    {
        SceneLights& s = keep().emplace_back();
        std::optional<Plane> plane =
            Plane::make({0, -2, 0}, normalize(Vec3(0.1, 1, 0.2)), Transform());
        s.scene->primitives.addPlane(*plane, s.scene->addMaterial(emitter({0.5, 0.5, 1}, true)));
        c.push_back({"plane", s.only()});
    }
    {
        SceneLights& s = keep().emplace_back();
        s.scene->background = {{0.2, 0.3, 0.4}, {1, 0.9, 0.6}};
        c.push_back({"background", s.only()});
    }
    {
        SceneLights& s = keep().emplace_back();
        // A small map: a bright spot in a dim sky.
        const int w = 16, h = 8;
        std::vector<float> rgb(w * h * 3, 0.2f);
        for (int k = 0; k < 3; ++k) rgb[(2 * w + 5) * 3 + k] = 30;
        s.scene->environment = std::make_shared<EnvironmentMap>(w, h, std::move(rgb));
        c.push_back({"environment map", s.only()});
    }
    return c;
}

/// The flux entering the target sphere: from sampleLe's rays, and from sampleLi over its surface.
struct Flux {
    test::MeanEstimate byEmission, byIrradiance;
};

Flux flux(const Light& light, uint64_t seed, int samples) {
    Flux f;
    Rng rng(seed);
    // A round sphere's sampleLi sees its near side only: its inside, which also emits, is
    // hidden from outside by the sphere itself. Its light paths into itself are left out too.
    const bool hidesItsInside = light.as<SphereLight>() != nullptr;
    for (int k = 0; k < samples; ++k) {
        std::optional<LightLeSample> s =
            light.sampleLe({rng.uniform(), rng.uniform()}, {rng.uniform(), rng.uniform()}, kTarget);
        if (s && hidesItsInside && dot(s->ray.dir, s->n) < 0) s.reset();
        f.byEmission.add(s ? s->beta.x : 0);
        // A point of the sphere, uniformly, and the light arriving there from outside.
        const Vec3 n = sampleUniformSphere({rng.uniform(), rng.uniform()});
        const Vec3 x = kTarget.center + n * kTarget.radius;
        std::optional<LightLiSample> li = light.sampleLi(x, {rng.uniform(), rng.uniform()});
        const double area = 4 * kPi * kTarget.radius * kTarget.radius;
        f.byIrradiance.add(li ? li->L.x * std::max(0.0, dot(li->wi, n)) / li->pdf * area : 0);
    }
    return f;
}

TEST(LightEmission, TheFluxOfSampleLeIsTheIrradianceOfSampleLiOverTheTarget) {
    for (const Case& c : cases()) {
        SCOPED_TRACE(c.name + ": " + testing::PrintToString(c.light));
        const Flux f = flux(c.light, 7, 400000);
        const double a = f.byEmission.mean(), b = f.byIrradiance.mean();
        const double se = std::hypot(f.byEmission.standardError(), f.byIrradiance.standardError());
        std::printf("%-22s by emission %.5f, by irradiance %.5f, %+.2f standard errors of %.2e\n",
                    c.name.c_str(), a, b, (a - b) / se, se);
        EXPECT_GT(b, 0);
        EXPECT_NEAR(a, b, 4 * se);
        EXPECT_LT(se, 0.02 * b);  // the comparison is sharp enough to catch a factor of pi
    }
}

TEST(LightEmission, PdfLeIsWhatSampleLeDrewAndBetaIsRadianceCosineOverTheDensities) {
    for (const Case& c : cases()) {
        SCOPED_TRACE(c.name + ": " + testing::PrintToString(c.light));
        Rng rng(11);
        int drawn = 0, mismatched = 0;
        for (int k = 0; k < 20000; ++k) {
            std::optional<LightLeSample> s = c.light.sampleLe(
                {rng.uniform(), rng.uniform()}, {rng.uniform(), rng.uniform()}, kTarget);
            if (!s) continue;
            ++drawn;
            ASSERT_GT(s->pdfPos, 0);
            ASSERT_GT(s->pdfDir, 0);
            // beta = L |cos| / (pdfPos pdfDir), the cosine at the light's surface (1 elsewhere).
            const double cosine = s->n == Vec3(0) ? 1 : std::abs(dot(s->n, s->ray.dir));
            const Vec3 expected = s->L * (cosine / (s->pdfPos * s->pdfDir));
            for (int ch = 0; ch < 3; ++ch)
                EXPECT_NEAR(s->beta[ch], expected[ch], 1e-9 * std::abs(expected[ch]));
            // pdfLe gives the same densities, with a delta's as 0.
            const LightLePdf p = c.light.pdfLe(s->p, s->n, s->ray.dir, kTarget);
            const bool deltaPos = c.light.isDelta() && !c.light.as<DirectionalLight>();
            const bool deltaDir = c.light.as<DirectionalLight>() != nullptr;
            const double pos = deltaPos ? 0 : s->pdfPos, dir = deltaDir ? 0 : s->pdfDir;
            if (std::abs(p.pos - pos) > 1e-9 * pos || std::abs(p.dir - dir) > 1e-9 * dir) {
                ++mismatched;
                ADD_FAILURE() << "pdfLe " << p.pos << ", " << p.dir << " for " << pos << ", "
                              << dir;
            }
            // The ray leaves from p, or just off the surface there.
            EXPECT_LE(length(s->ray.origin - s->p), 1e-4 * (1 + length(s->p)));
        }
        EXPECT_GT(drawn, 5000);
        EXPECT_EQ(mismatched, 0);
    }
}

TEST(LightEmission, LightPathsAimAtTheTarget) {
    for (const Case& c : cases()) {
        SCOPED_TRACE(c.name);
        Rng rng(13);
        for (int k = 0; k < 2000; ++k) {
            std::optional<LightLeSample> s = c.light.sampleLe(
                {rng.uniform(), rng.uniform()}, {rng.uniform(), rng.uniform()}, kTarget);
            if (!s) continue;
            // The ray passes within the target sphere (a little beyond, for rays off a surface).
            const Vec3 toCenter = kTarget.center - s->ray.origin;
            const double along = dot(toCenter, s->ray.dir);
            const double miss = length(toCenter - s->ray.dir * along);
            EXPECT_GT(along, 0);
            EXPECT_LE(miss, kTarget.radius * (1 + 1e-6));
        }
    }
}

TEST(LightSampling, PdfLiIsWhatSampleLiDrewForLightsAPathCanFind) {
    for (const Case& c : cases()) {
        if (c.light.isDelta() || c.light.as<ShapeLight>()) continue;  // shapes: light_sampler_test
        SCOPED_TRACE(c.name + ": " + testing::PrintToString(c.light));
        Rng rng(17);
        int checked = 0;
        for (int k = 0; k < 5000; ++k) {
            const Vec3 p = sampleUniformSphere({rng.uniform(), rng.uniform()}) * 0.9;
            std::optional<LightLiSample> s = c.light.sampleLi(p, {rng.uniform(), rng.uniform()});
            if (!s) continue;
            const Vec3 q = std::isfinite(s->distance) ? p + s->wi * s->distance : Vec3(0);
            Vec3 n(0);
            if (const auto* t = c.light.as<TriangleLight>()) n = t->n;
            if (const auto* sph = c.light.as<SphereLight>()) n = normalize(q - sph->center);
            const double pdf = c.light.pdfLi(p, LightPoint{q, n, s->wi});
            EXPECT_NEAR(pdf, s->pdf, 1e-6 * s->pdf) << testing::PrintToString(*s);
            EXPECT_NEAR(c.light.pdfLi(p, LightPoint{q, n, s->wi}, 0.25), 0.25 * pdf, 1e-12 * pdf);
            ++checked;
        }
        EXPECT_GT(checked, 1000);
    }
}

TEST(SpotLight, ShinesFullyWithinItsInnerConeNotBeyondItsOuterAndFadesBetween) {
    const SpotLight spot{{0, 2, 0}, {0, -1, 0}, {8, 8, 8}, {0, 0, 1}, std::cos(0.3), std::cos(0.5)};
    EXPECT_TRUE(spot.isDelta());
    auto at = [&](double angle) {  // a point 2 below the light, `angle` off the axis
        return spot.sampleLi({2 * std::tan(angle), 0, 0}, {0.5, 0.5});
    };
    std::optional<LightLiSample> below = at(0);
    ASSERT_TRUE(below);
    EXPECT_EQ(below->L, Vec3(2));  // 8 over 2^2
    EXPECT_EQ(below->pdf, 1);
    EXPECT_TRUE(below->delta);
    std::optional<LightLiSample> inner = at(0.29);
    ASSERT_TRUE(inner);
    EXPECT_NEAR(inner->L.x, 8 / (4 / std::pow(std::cos(0.29), 2)), 1e-12);
    EXPECT_FALSE(at(0.51));
    // Between: the square of the cosine's linear ramp, and less the further out.
    double last = 1;
    for (double angle = 0.31; angle < 0.5; angle += 0.02) {
        const double f = spot.falloff({std::sin(angle), -std::cos(angle), 0});
        const double ramp = (std::cos(angle) - std::cos(0.5)) / (std::cos(0.3) - std::cos(0.5));
        EXPECT_NEAR(f, ramp * ramp, 1e-12);
        EXPECT_LT(f, last);
        last = f;
    }
    // The light tree sees a point emitting within the outer cone.
    std::optional<LightBounds> b = spot.bounds();
    ASSERT_TRUE(b);
    EXPECT_EQ(b->w, Vec3(0, -1, 0));
    EXPECT_EQ(b->cosThetaE, std::cos(0.5));
    EXPECT_GT(b->importance({0, 0, 0}, {0, 1, 0}), 0);
    EXPECT_EQ(b->importance({0, 4, 0}, {0, -1, 0}), 0);  // behind it
}

TEST(LightPrinting, EachLightSaysWhatItIs) {
    std::ostringstream out;
    out << Light(PointLight{{1, 2, 3}, {4, 5, 6}});
    EXPECT_EQ(out.str(), "PointLight{at (1, 2, 3), intensity (4, 5, 6), attenuation (1, 0, 0)}");
    for (const Case& c : cases()) {
        std::ostringstream o;
        o << c.light;
        const std::string text = o.str();
        EXPECT_NE(text.find("Light{"), std::string::npos) << text;
        EXPECT_EQ(text.back(), '}') << text;
    }
    std::ostringstream spec;
    LightSpec quad;
    quad.kind = LightSpec::Kind::Quad;
    quad.edge1 = {1, 0, 0};
    quad.edge2 = {0, 0, 1};
    quad.color = Vec3(2);
    spec << quad;
    EXPECT_EQ(spec.str(),
              "LightSpec{quad at (0, 0, 0), edges (1, 0, 0) and (0, 0, 1), radiance (2, 2, 2)}");
}

// glTF's range: a point or spot light's intensity over d^2 times max(min(1 - (d / r)^4, 1), 0),
// nothing at or beyond the range, the same as without one where no range is given.
TEST(LightRange, WindowsPointAndSpotLightsAsTheGltfSpecRecommends) {
    LightSpec spec;
    spec.position = {0, 4, 0};
    spec.color = Vec3(8);
    spec.attenuation = {0, 0, 1};
    spec.axis = {0, -1, 0};
    spec.cosInner = std::cos(0.6);
    spec.cosOuter = std::cos(0.7);
    for (LightSpec::Kind kind : {LightSpec::Kind::Point, LightSpec::Kind::Spot}) {
        spec.kind = kind;
        spec.range = 0;
        const Light unlimited = lightFromSpec(spec);
        spec.range = 5;
        const Light ranged = lightFromSpec(spec);
        for (double d : {0.5, 2.0, 3.0, 4.5, 4.99}) {
            const Vec3 p(0, 4 - d, 0);  // straight below, on the spot's axis
            const auto a = unlimited.sampleLi(p, {0.5, 0.5});
            const auto b = ranged.sampleLi(p, {0.5, 0.5});
            ASSERT_TRUE(a && b) << d;
            const double x = d / 5, expected = 8 / (d * d) * (1 - x * x * x * x);
            EXPECT_NEAR(a->L.y, 8 / (d * d), 1e-9 * a->L.y) << d;
            EXPECT_NEAR(b->L.y, expected, 1e-9 * a->L.y) << d;
        }
        EXPECT_FALSE(ranged.sampleLi({0, -1, 0}, {0.5, 0.5}));  // 5 away: the window is 0
        EXPECT_FALSE(ranged.sampleLi({0, -3, 0}, {0.5, 0.5}));  // beyond
        EXPECT_TRUE(unlimited.sampleLi({0, -3, 0}, {0.5, 0.5}));
    }
    EXPECT_EQ(rangeWindow(3, 0), 1);
    EXPECT_EQ(rangeWindow(0, 2), 1);
}

}  // namespace
}  // namespace glint
