// Transport modes (bsdf_sample.h's TransportMode): every lobe that transmits light, with
// radiance and with importance. Importance is radiance without refraction's (n_o / n_i)^2, so
// that it is the adjoint of radiance: f_importance(wo, wi) = f_radiance(wi, wo) wherever the
// lobe is reciprocal apart from refraction, and a light path's power is conserved where the
// boundary loses nothing.

#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "glint/math/rng.h"
#include "glint/render/bsdfs/bsdf.h"
#include "glint/render/bsdfs/optics.h"
#include "unit/render/bsdfs/bsdf_checks.h"
#include "unit/statistics.h"

namespace glint {
namespace {

using test::direction;
using test::uniform2;
constexpr auto kRadiance = TransportMode::Radiance;
constexpr auto kImportance = TransportMode::Importance;

struct Case {
    std::string name;
    Bsdf bsdf;
    /// Whether f(wo, wi) / n_o^2 = f(wi, wo) / n_i^2 (only refraction breaks symmetry).
    bool reciprocal;
};

MetallicRoughness glassVolume(double alpha) {
    MetallicRoughness m{Vec3(0.9, 0.8, 0.7), 0, alpha, 1, 1.5, false};
    return m;
}

/// Every lobe that transmits: glass (smooth and rough, eta above and below 1) and glTF's
/// transmission (a refracting volume, a thin wall, diffuse transmission, with its layers).
std::vector<Case> transmissiveCases() {
    MetallicRoughness thin{Vec3(0.8), 0, 0.2, 0.7, 1.5, true};
    MetallicRoughness diffuseThrough{Vec3(0.6, 0.7, 0.8), 0, 0.3, 0, 1.4, true};
    diffuseThrough.diffuseTransmission = 0.6;
    MetallicRoughness coated = glassVolume(0.2);
    coated.coat = {0.7, 0.05, Vec3(0, 0, 1)};
    coated.sheen = {Vec3(0.3), 0.3};
    return {
        {"smooth glass", Dielectric{1.5, Vec3(0.9, 0.8, 1), 0}, true},
        {"rough glass", Dielectric{1.5, Vec3(0.9, 0.8, 1), 0.3}, true},
        {"rough glass, eta below 1", Dielectric{1 / 1.33, Vec3(1), 0.5}, true},
        {"glTF volume, rough", glassVolume(0.16), true},
        {"glTF volume, nearly smooth", glassVolume(MetallicRoughness::kMinAlpha), true},
        {"glTF thin wall", thin, false},
        {"glTF diffuse transmission", diffuseThrough, false},
        {"glTF volume, coated and sheened", coated, false},
    };
}

/// n_i / n_o for light going from wo's side to wi's side of a lobe whose inside (below) has
/// relative index `eta` (1 if it refracts into nothing).
double indexRatio(const Bsdf& b, const Vec3& wo, const Vec3& wi) {
    if (!(wo.z * wi.z < 0)) return 1;
    const double eta = b.relativeEta().value_or(1);
    return wo.z > 0 ? eta : 1 / eta;
}

TEST(TransportMode, EveryTransmissiveLobeIsAdjointToItself) {
    Rng rng(41);
    for (const Case& c : transmissiveCases()) {
        SCOPED_TRACE(c.name + ": " + testing::PrintToString(c.bsdf));
        ASSERT_TRUE(c.bsdf.transmits());
        int through = 0;
        for (int k = 0; k < 4000; ++k) {
            const Vec3 wo = direction(179 * rng.uniform() + 0.5, 360 * rng.uniform());
            const Vec3 wi = direction(179 * rng.uniform() + 0.5, 360 * rng.uniform());
            const Vec3 radiance = c.bsdf.eval(wo, wi, kRadiance);
            const Vec3 importance = c.bsdf.eval(wo, wi, kImportance);
            // Importance is radiance without the radiance's compression: (n_i / n_o)^2 more.
            const double ratio = indexRatio(c.bsdf, wo, wi);
            for (int ch = 0; ch < 3; ++ch)
                EXPECT_NEAR(importance[ch], radiance[ch] * ratio * ratio,
                            1e-12 * std::abs(importance[ch]) + 1e-300)
                    << testing::PrintToString(wo) << " -> " << testing::PrintToString(wi);
            // The densities do not depend on what is carried.
            EXPECT_EQ(c.bsdf.pdf(wo, wi, kRadiance), c.bsdf.pdf(wo, wi, kImportance));
            if (!c.reciprocal) continue;
            // The adjoint: importance from wo to wi is radiance from wi to wo.
            const Vec3 back = c.bsdf.eval(wi, wo, kRadiance);
            for (int ch = 0; ch < 3; ++ch)
                EXPECT_NEAR(importance[ch], back[ch], 1e-9 * std::abs(back[ch]) + 1e-14)
                    << testing::PrintToString(wo) << " -> " << testing::PrintToString(wi);
            if (wo.z * wi.z < 0 && importance.y > 0) ++through;
        }
        // The relation was checked where light goes through (not only where f is 0).
        if (c.reciprocal && c.bsdf.as<Dielectric>() && c.bsdf.as<Dielectric>()->rough()) {
            EXPECT_GT(through, 300);
        }
    }
}

TEST(TransportMode, SampledDirectionsAreTheSameAndOnlyRefractionsWeighDifferently) {
    Rng rng(43);
    for (const Case& c : transmissiveCases()) {
        SCOPED_TRACE(c.name + ": " + testing::PrintToString(c.bsdf));
        int refracted = 0;
        for (int k = 0; k < 20000; ++k) {
            const Vec3 wo = direction(179 * rng.uniform() + 0.5, 360 * rng.uniform());
            const double uc = rng.uniform();
            const Point2 u = uniform2(rng);
            const std::optional<BsdfSample> r = c.bsdf.sample(wo, uc, u, kRadiance);
            const std::optional<BsdfSample> i = c.bsdf.sample(wo, uc, u, kImportance);
            ASSERT_EQ(r.has_value(), i.has_value());
            if (!r) continue;
            EXPECT_EQ(r->wi, i->wi) << *r << " / " << *i;
            EXPECT_EQ(r->pdf, i->pdf) << *r << " / " << *i;
            EXPECT_EQ(r->flags, i->flags) << *r << " / " << *i;
            const double ratio = indexRatio(c.bsdf, wo, r->wi);
            const Vec3 expected = r->weight() * (ratio * ratio);
            for (int ch = 0; ch < 3; ++ch)
                EXPECT_NEAR(i->weight()[ch], expected[ch], 1e-12 * std::abs(expected[ch]))
                    << *r << " / " << *i;
            if (ratio != 1) ++refracted;
        }
        if (c.bsdf.relativeEta()) {
            EXPECT_GT(refracted, 1000);
        }
    }
}

// A smooth lossless boundary neither creates nor destroys power: a light path's expected weight
// through it is 1 (its radiance weight is R + T (n_o / n_i)^2 instead:
// bsdf_test.cpp's furnace).
TEST(TransportMode, ASmoothBoundaryConservesThePowerOfLightPaths) {
    Rng rng(47);
    for (double eta : {1.5, 1.33, 1 / 1.5})
        for (double theta : {0.0, 30.0, 60.0, 85.0, 120.0, 150.0, 175.0}) {
            const Bsdf glass = Dielectric{eta, Vec3(1)};
            const Vec3 wo = direction(theta);
            test::MeanEstimate power;
            for (int k = 0; k < 20000; ++k) {
                const double uc = rng.uniform();
                std::optional<BsdfSample> s = glass.sample(wo, uc, uniform2(rng), kImportance);
                ASSERT_TRUE(s);
                EXPECT_NEAR(s->weight().x, 1, 1e-12) << *s;
                power.add(s->weight().x);
            }
            EXPECT_NEAR(power.mean(), 1, 1e-12) << "eta " << eta << ", theta " << theta;
        }
}

// Lobes that do not transmit carry the same in both modes, to the bit.
TEST(TransportMode, OpaqueLobesAreTheSameForRadianceAndImportance) {
    MetallicRoughness clay{Vec3(0.7, 0.4, 0.2), 0.2, 0.3};
    clay.sheen = {Vec3(0.4), 0.2};
    const std::vector<Bsdf> opaque = {Lambertian{Vec3(0.5)}, Conductor{Vec3(0.9, 0.6, 0.3), 0.2},
                                      Conductor{Vec3(0.9), 0},
                                      DiffuseSpecular{Vec3(0.3), Vec3(0.5), 0.1}, clay};
    Rng rng(53);
    for (const Bsdf& b : opaque) {
        SCOPED_TRACE(testing::PrintToString(b));
        EXPECT_FALSE(b.transmits());
        for (int k = 0; k < 2000; ++k) {
            const Vec3 wo = direction(179 * rng.uniform() + 0.5, 360 * rng.uniform());
            const Vec3 wi = direction(179 * rng.uniform() + 0.5, 360 * rng.uniform());
            EXPECT_EQ(b.eval(wo, wi, kRadiance), b.eval(wo, wi, kImportance));
            const double uc = rng.uniform();
            const Point2 u = uniform2(rng);
            const auto r = b.sample(wo, uc, u, kRadiance), i = b.sample(wo, uc, u, kImportance);
            ASSERT_EQ(r.has_value(), i.has_value());
            if (r) {
                EXPECT_EQ(r->f, i->f);
            }
        }
    }
}

}  // namespace
}  // namespace glint
