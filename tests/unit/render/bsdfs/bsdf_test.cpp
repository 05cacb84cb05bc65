// BSDFs: sample() against pdf() by chi-square tests, white furnaces, reciprocity, the delta
// lobes against Schlick, Fresnel and Snell, the rough dielectric's weights and its smooth
// limit, and the course material's mapping.

#include "glint/render/bsdfs/bsdf.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <numbers>
#include <ostream>
#include <string>
#include <vector>

#include "glint/math/rng.h"
#include "glint/render/bsdfs/ggx_albedo.h"
#include "glint/render/bsdfs/optics.h"
#include "unit/render/bsdfs/bsdf_checks.h"
#include "unit/statistics.h"
#include "unit/test_support.h"

namespace glint {
namespace {

using test::expectNear;

using test::albedo;
using test::chiSquare;
using test::ChiSquareRun;
using test::direction;
using test::kAlpha;
using test::kPi;
using test::uniform2;

struct ChiCase {
    std::string name;
    Bsdf bsdf;
    Vec3 wo;
    uint64_t seed = 0;  ///< Its own random numbers: the tests are independent.
};

std::vector<ChiCase> chiCases() {
    std::vector<ChiCase> cases;
    for (double theta : {10.0, 60.0, 120.0})  // 120: wo below, the lobe's mirror image
        cases.push_back(
            {"lambert_" + std::to_string(int(theta)), {Lambertian{Vec3(0.8)}}, direction(theta)});
    for (double alpha : {0.1, 0.3, 0.7, 1.0})
        for (double theta : {0.0, 40.0, 80.0})
            cases.push_back(
                {"ggx_a" + std::to_string(int(alpha * 100)) + "_" + std::to_string(int(theta)),
                 {Conductor{Vec3(0.9, 0.6, 0.3), alpha}},
                 direction(theta)});
    cases.push_back({"ggx_a30_below", {Conductor{Vec3(1), 0.3}}, direction(140)});
    // F0 = 1 near grazing, where the compensation's cosine-weighted share is largest (about
    // 0.5 at alpha = 1), and the single-scattering lobe alone.
    for (double alpha : {0.05, 0.6, 1.0})
        cases.push_back({"ggx_white_a" + std::to_string(int(alpha * 100)) + "_85",
                         {Conductor{Vec3(1), alpha}},
                         direction(85)});
    for (double alpha : {0.3, 1.0})
        cases.push_back({"ggx_single_a" + std::to_string(int(alpha * 100)) + "_40",
                         {Conductor{Vec3(0.9, 0.6, 0.3), alpha, false}},
                         direction(40)});
    for (double theta : {30.0, 70.0})
        cases.push_back({"diffuse_glossy_" + std::to_string(int(theta)),
                         {DiffuseSpecular{Vec3(0.5), Vec3(0.4), 0.2}},
                         direction(theta)});
    cases.push_back(
        {"diffuse_rough_60", {DiffuseSpecular{Vec3(0.3), Vec3(0.7), 0.8}}, direction(60)});
    cases.push_back(
        {"diffuse_mirror_45", {DiffuseSpecular{Vec3(0.5), Vec3(0.4), 0}}, direction(45)});
    // Rough glass and water, seen from outside and from inside (125: beyond the critical angle
    // of both, 41.8 and 48.8 degrees from the normal; 165: within it).
    for (double eta : {1.5, 1.33})
        for (double alpha : {0.1, 0.3, 0.7})
            for (double theta : {10.0, 50.0, 80.0, 125.0, 165.0})
                cases.push_back({"dielectric_e" + std::to_string(int(std::round(eta * 100))) +
                                     "_a" + std::to_string(int(alpha * 100)) + "_" +
                                     std::to_string(int(theta)),
                                 {Dielectric{eta, Vec3(0.9, 0.8, 0.7), alpha}},
                                 direction(theta)});
    // glTF's metallic-roughness: dielectric, half metal and metal; a volume that refracts.
    for (double metallic : {0.0, 0.5, 1.0})
        for (double alpha : {0.05, 0.3, 0.8})
            for (double theta : {20.0, 75.0, 140.0})
                cases.push_back({"gltf_m" + std::to_string(int(metallic * 10)) + "_a" +
                                     std::to_string(int(alpha * 100)) + "_" +
                                     std::to_string(int(theta)),
                                 {MetallicRoughness{Vec3(0.8, 0.5, 0.2), metallic, alpha}},
                                 direction(theta)});
    for (double theta : {30.0, 150.0})
        cases.push_back({"gltf_volume_" + std::to_string(int(theta)),
                         {MetallicRoughness{Vec3(0.9), 0.2, 0.3, 0.7, 1.5, false}},
                         direction(theta)});
    for (size_t k = 0; k < cases.size(); ++k) cases[k].seed = 1000 + k;
    return cases;
}

void PrintTo(const ChiCase& c, std::ostream* os) { *os << c.name; }

class ChiSquare : public testing::TestWithParam<ChiCase> {};

TEST_P(ChiSquare, SampledDirectionsFollowThePdf) {
    const ChiCase& c = GetParam();
    const double level = test::sidak(kAlpha, static_cast<int>(chiCases().size()));
    ChiSquareRun run = chiSquare(c.bsdf, c.bsdf, c.wo, c.seed);
    std::printf("%s: chi2 %.1f, %d dof, p-value %.4f (significance %.2e per test)\n",
                c.name.c_str(), run.result.chi2, run.result.dof, run.result.pValue, level);
    EXPECT_FALSE(run.result.outsideSupport) << c.name;
    EXPECT_GT(run.result.pValue, level) << c.name << ": chi2 " << run.result.chi2 << ", "
                                        << run.result.dof << " degrees of freedom";
    // What sample() returns is what eval() and pdf() say.
    EXPECT_LT(run.worstMismatch, 1e-9) << c.name;
}

INSTANTIATE_TEST_SUITE_P(Bsdf, ChiSquare, testing::ValuesIn(chiCases()),
                         [](const testing::TestParamInfo<ChiCase>& p) { return p.param.name; });

TEST(ChiSquarePower, ADensityOfTheWrongRoughnessOrShapeIsRejected) {
    const double level = test::sidak(kAlpha, static_cast<int>(chiCases().size()));
    // GGX drawn with alpha 0.3, tested against the density for 0.32.
    ChiSquareRun ggx =
        chiSquare({Conductor{Vec3(1), 0.3}}, {Conductor{Vec3(1), 0.32}}, direction(40), 7);
    EXPECT_LT(ggx.result.pValue, level) << "chi2 " << ggx.result.chi2;
    // Cosine-weighted directions tested against the mixture's density with a mirror share of
    // 5% (the diffuse density scaled by 0.95 and 5% expected in the "no density" bin).
    ChiSquareRun lambert = chiSquare(
        {Lambertian{Vec3(1)}}, {DiffuseSpecular{Vec3(0.95), Vec3(0.05), 0}}, direction(40), 7);
    EXPECT_LT(lambert.result.pValue, level) << "chi2 " << lambert.result.chi2;
    // Rough glass drawn with eta 1.5, tested against the density for 1.47: the split between
    // reflection and transmission and the bend of the transmitted lobe are a little off.
    ChiSquareRun glass = chiSquare({Dielectric{1.5, Vec3(1), 0.3}},
                                   {Dielectric{1.47, Vec3(1), 0.3}}, direction(40), 7);
    EXPECT_LT(glass.result.pValue, level) << "chi2 " << glass.result.chi2;
    // The compensated conductor (F0 = 1, alpha 1, 60 degrees: a cosine-weighted share p of
    // about 0.4) against its density with that share 3% too large, p -> 1.03 p: since
    // pdf = (1 - p) pdf_ss + p cos / pi, that density is pdf + 0.03 (pdf - pdf_ss).
    Vec3 wo = direction(60);
    Conductor white{Vec3(1), 1.0}, single{Vec3(1), 1.0, false};
    ChiSquareRun share = chiSquare(
        {white},
        [&](const Vec3& wi) {
            return white.pdf(wo, wi) + 0.03 * (white.pdf(wo, wi) - single.pdf(wo, wi));
        },
        wo, 7);
    EXPECT_LT(share.result.pValue, level) << "chi2 " << share.result.chi2;
    std::printf(
        "wrong alpha: p-value %.3g; wrong mass: p-value %.3g; wrong eta: p-value %.3g; wrong "
        "cosine share: p-value %.3g\n",
        ggx.result.pValue, lambert.result.pValue, glass.result.pValue, share.result.pValue);
}

TEST(ChiSquareStatistics, PValuesMatchTablesOfTheChiSquareDistribution) {
    // 95th percentiles (any statistics table).
    EXPECT_NEAR(test::chiSquarePValue(3.841459, 1), 0.05, 1e-6);
    EXPECT_NEAR(test::chiSquarePValue(18.307038, 10), 0.05, 1e-6);
    EXPECT_NEAR(test::chiSquarePValue(124.342113, 100), 0.05, 1e-6);
    // The median of 2 degrees of freedom is 2 ln 2 (the exponential distribution).
    EXPECT_NEAR(test::chiSquarePValue(2 * std::log(2.0), 2), 0.5, 1e-12);
    EXPECT_NEAR(test::sidak(0.01, 1), 0.01, 1e-15);
    EXPECT_NEAR(test::sidak(0.01, 19), 5.288e-4, 1e-6);
}

// ---- White furnace: directional albedo, the mean of f |cos| / pdf ----

TEST(WhiteFurnace, LambertOfAlbedoOneAndMirrorsOfReflectanceOneReflectEverything) {
    Rng rng(3);
    for (double theta : {0.0, 30.0, 60.0, 89.0, 100.0, 170.0}) {
        for (const Bsdf& b : {Bsdf{Lambertian{Vec3(1)}}, Bsdf{Conductor{Vec3(1), 0}},
                              Bsdf{DiffuseSpecular{Vec3(0.6), Vec3(0.4), 0}}})
            for (int k = 0; k < 1000; ++k) {
                double uc = rng.uniform();
                std::optional<BsdfSample> s = b.sample(direction(theta), uc, uniform2(rng));
                if (!s) continue;  // the disk's rim, density 0: never in practice
                // Every sample's weight is exactly the albedo, so their mean is too.
                EXPECT_NEAR(s->weight().x, 1, 1e-12) << theta;
                EXPECT_NEAR(s->weight().z, 1, 1e-12) << theta;
            }
    }
}

TEST(WhiteFurnace, SmoothDielectricConservesEnergyAndCompressesRefractedRadiance) {
    Rng rng(5);
    for (double eta : {1.5, 1.33, 1 / 1.5})
        for (double theta : {0.0, 30.0, 60.0, 85.0, 120.0, 150.0, 175.0}) {
            Dielectric d{eta, Vec3(1)};
            Vec3 wo = direction(theta);
            double etaRel = wo.z > 0 ? 1 / eta : eta;  // wo's side over the other side
            test::MeanEstimate radiance;
            for (int k = 0; k < 20000; ++k) {
                double uc = rng.uniform();
                std::optional<BsdfSample> s = d.sample(wo, uc, uniform2(rng));
                ASSERT_TRUE(s);
                double w = s->weight().x;
                // Energy: every reflection keeps its weight 1, every refraction changes only
                // the solid angle, by etaRel^2.
                EXPECT_NEAR(s->isTransmission() ? w / (etaRel * etaRel) : w, 1, 1e-12);
                radiance.add(w);
            }
            double r = fresnelDielectric(std::abs(wo.z), etaRel);
            EXPECT_NEAR(radiance.mean(), r + (1 - r) * etaRel * etaRel,
                        4 * radiance.standardError() + 1e-12)
                << "eta " << eta << ", theta " << theta;
        }
}

/// The GGX conductor's directional albedo with F = 1, by quadrature of D G2 / (4 cos_o) over
/// the hemisphere (the BRDF times cos_i), from optics.h's D and G alone.
double ggxAlbedoByQuadrature(double alpha, const Vec3& wo) {
    Ggx ggx{alpha};
    auto overPhi = [&](double cosI) {
        double sinI = std::sqrt(std::max(0.0, 1 - cosI * cosI));
        auto f = [&](double phi) {
            Vec3 wi(sinI * std::cos(phi), sinI * std::sin(phi), cosI);
            Vec3 h = normalize(wo + wi);
            return ggx.d(h) * ggx.g2(wo, wi) / (4 * wo.z);
        };
        return test::integrate(f, 0, 2 * kPi, 1e-10, 16);
    };
    return test::integrate(overPhi, 0, 1, 1e-8, 16);
}

TEST(WhiteFurnace, GgxConductorLosesOnlyWhatSingleScatteringMisses) {
    uint64_t seed = 11;
    for (double alpha : {0.1, 0.3, 0.6, 1.0})
        for (double theta : {0.0, 45.0, 75.0}) {
            Vec3 wo = direction(theta);
            double exact = ggxAlbedoByQuadrature(alpha, wo);
            test::MeanEstimate e =
                albedo({Conductor{Vec3(1), alpha, false}}, wo, 200000, seed++)[0];
            std::printf("alpha %.1f, theta %2.0f: albedo %.5f +- %.5f (quadrature %.5f)\n", alpha,
                        theta, e.mean(), e.standardError(), exact);
            EXPECT_NEAR(e.mean(), exact, 4 * e.standardError() + 1e-6) << alpha << " " << theta;
            EXPECT_LE(exact, 1 + 1e-6);
            // The compensation's table holds the same albedo.
            EXPECT_NEAR(GgxAlbedo(alpha)(wo.z), exact, ggx_albedo_table::kMaxError)
                << alpha << " " << theta;
        }
}

/// The integral of f(wi) cos_i over the upper hemisphere, by quadrature over the polar angle
/// (in which the compensation's E(cos_i) is smooth up to the normal; in cos_i it is not).
template <typename F>
double hemisphereIntegral(const F& f) {
    auto overPhi = [&](double theta) {
        double cosI = std::cos(theta), sinI = std::sin(theta);
        auto g = [&](double phi) {
            return f(Vec3(sinI * std::cos(phi), sinI * std::sin(phi), cosI)) * cosI * sinI;
        };
        return test::integrate(g, 0, 2 * kPi, 1e-10, 16);
    };
    return test::integrate(overPhi, 0, kPi / 2, 1e-9, 16);
}

// Kulla and Conty's compensation gives back what single scattering loses: with F0 = 1 the
// conductor reflects everything at every angle and roughness, to the error of the albedo table
// (ggx_albedo.h), measured by its generator.
TEST(WhiteFurnace, CompensatedGgxConductorOfReflectanceOneReflectsEverything) {
    const double tableError = ggx_albedo_table::kMaxError;
    uint64_t seed = 41;
    for (double alpha : {0.1, 0.3, 0.6, 1.0})
        for (double theta : {0.0, 30.0, 60.0, 80.0, 88.0, 150.0}) {  // 150: below, two-sided
            Vec3 wo = direction(theta);
            test::MeanEstimate e = albedo({Conductor{Vec3(1), alpha}}, wo, 200000, seed++)[0];
            std::printf("alpha %.1f, theta %3.0f: albedo %.5f +- %.5f\n", alpha, theta, e.mean(),
                        e.standardError());
            EXPECT_NEAR(e.mean(), 1, 5 * e.standardError() + tableError) << alpha << " " << theta;
        }
    // The same without noise: eval() integrated over the hemisphere.
    for (double alpha : {0.1, 0.3, 0.6, 1.0})
        for (double theta : {0.0, 75.0, 88.0}) {
            Vec3 wo = direction(theta);
            Conductor white{Vec3(1), alpha};
            double a = hemisphereIntegral([&](const Vec3& wi) { return white.eval(wo, wi).x; });
            std::printf("alpha %.1f, theta %3.0f: albedo by quadrature 1 %+.1e\n", alpha, theta,
                        a - 1);
            EXPECT_NEAR(a, 1, tableError + 1e-6) << alpha << " " << theta;
        }
    // The course's material: its specular lobe is this conductor, so diffuse + specular = 1
    // reflects everything too.
    for (double theta : {0.0, 60.0, 85.0}) {
        test::MeanEstimate e = albedo({DiffuseSpecular{Vec3(0.3), Vec3(0.7), 0.8}},
                                      direction(theta), 200000, seed++)[0];
        EXPECT_NEAR(e.mean(), 1, 5 * e.standardError() + tableError) << theta;
    }
}

// With a coloured F0 the compensation adds F_ms (1 - E(mu_o)) to the albedo, F_ms = F_avg^2
// E_avg / (1 - F_avg (1 - E_avg)) with F_avg = f0 + (1 - f0) / 21 the hemispherical average of
// Schlick's Fresnel: the light that leaves after two or more bounces, each reflecting F_avg.
// F_ms <= F_avg^2 < 1, so no more than single scattering leaves out (the next test samples
// such conductors' albedos: below 1).
TEST(WhiteFurnace, CompensationOfAColouredConductorAddsKullaContysShare) {
    for (Vec3 f0 : {Vec3(0.95, 0.64, 0.54), Vec3(0.5, 0.04, 0.2)})
        for (double alpha : {0.1, 0.3, 0.6, 1.0})
            for (double theta : {0.0, 60.0, 85.0}) {
                Vec3 wo = direction(theta);
                Conductor whole{f0, alpha}, single{f0, alpha, false};
                GgxAlbedo e(alpha);
                for (int c = 0; c < 3; ++c) {
                    double favg = f0[c] + (1 - f0[c]) / 21, eavg = e.average();
                    double fms = favg * favg * eavg / (1 - favg * (1 - eavg));
                    // f - f_ss is f_ms, smooth: its integral is exact to the quadrature's 1e-8.
                    double added = hemisphereIntegral([&](const Vec3& wi) {
                        return whole.eval(wo, wi)[c] - single.eval(wo, wi)[c];
                    });
                    EXPECT_NEAR(added, fms * (1 - e(wo.z)), 1e-7)
                        << f0[c] << " " << alpha << " " << theta;
                    EXPECT_LT(fms, favg * favg);
                }
            }
}

TEST(WhiteFurnace, NoBsdfReflectsMoreThanItReceives) {
    std::vector<Bsdf> bsdfs = {
        {Conductor{Vec3(0.95, 0.64, 0.54), 0.05}},
        {Conductor{Vec3(0.95, 0.64, 0.54), 0.5}},
        {Conductor{Vec3(0.99, 0.9, 0.04), 1.0}},
        {DiffuseSpecular{Vec3(0.7), Vec3(0.3), 0.3}},
        {Dielectric{1.5, Vec3(1, 0.8, 0.5)}},
        {MetallicRoughness{Vec3(1), 1, 0.02}},
        {MetallicRoughness{Vec3(0.8), 0, 0.3}},
        {MetallicRoughness{Vec3(1), 0.3, 0.6, 0.8}},  // a thin transmitting wall
        // The course's materials at their worst: colours beyond 1 and below 0.
        bsdfFromMaterial([] {
            Material m;
            m.diffuse = {5, 1, 0.2};
            m.specular = {2, -1, 0.9};
            m.roughness = 0.4;
            return m;
        }()),
        bsdfFromMaterial([] {
            Material m;
            m.diffuse = {1, 1, 1};
            m.specular = {1, 1, 1};
            return m;
        }()),
    };
    // Those of albedo 1 (diffuse + specular = 1) reach it to the GGX table's error.
    const double tableError = ggx_albedo_table::kMaxError;
    for (size_t k = 0; k < bsdfs.size(); ++k)
        for (double theta : {0.0, 50.0, 85.0, 130.0}) {
            auto e = albedo(bsdfs[k], direction(theta), 100000, 13);
            for (int c = 0; c < 3; ++c)
                EXPECT_LE(e[c].mean(), 1 + 4 * e[c].standardError() + tableError)
                    << "bsdf " << k << ", theta " << theta << ", channel " << c;
        }
}

// ---- glTF's metallic-roughness BRDF ----

TEST(MetallicRoughness, TheSpecificationsDielectricGainsALittleEnergyOnlyNearGrazing) {
    // The specification weighs the diffuse lobe by 1 - F(wo.h), which near grazing views is
    // smaller than the specular lobe's share F(cos_o): a white dielectric then reflects a few
    // percent more than it receives (7.5% at 85 degrees). Glint keeps the specification's
    // model (as glTF viewers do); this bounds the gain.
    const MetallicRoughness white{Vec3(1), 0, 0.3};
    for (double theta : {0.0, 50.0, 70.0, 85.0}) {
        auto e = albedo({white}, direction(theta), 100000, 17);
        EXPECT_LE(e[1].mean(), (theta <= 50 ? 1.0 : 1.1) + 4 * e[1].standardError()) << theta;
        EXPECT_GT(e[1].mean(), 0.9) << theta;
    }
}

TEST(MetallicRoughness, IsTheSpecificationsMixOfAConductorAndAFresnelWeightedDielectric) {
    // Metal: the single-scattering GGX conductor of F0 = base colour. Dielectric: F_d of
    // F0 = 0.04 on the specular lobe (the conductor of F0 = 0.04) and 1 - F_d on the diffuse.
    const Vec3 base(0.9, 0.5, 0.1);
    for (double alpha : {0.05, 0.4, 1.0})
        for (double thetaO : {10.0, 60.0, 85.0})
            for (double thetaI : {0.0, 45.0, 80.0}) {
                const Vec3 wo = direction(thetaO), wi = direction(thetaI, 200);
                expectNear(MetallicRoughness{base, 1, alpha}.eval(wo, wi),
                           Conductor{base, alpha, false}.eval(wo, wi), 1e-12);
                const Vec3 h = normalize(wo + wi);
                const double m = 1 - dot(wo, h), fd = 0.04 + 0.96 * m * m * m * m * m;
                const Vec3 dielectric = base * ((1 - fd) / std::numbers::pi) +
                                        Conductor{Vec3(0.04), alpha, false}.eval(wo, wi);
                expectNear(MetallicRoughness{base, 0, alpha}.eval(wo, wi), dielectric, 1e-12);
                expectNear(MetallicRoughness{base, 0.25, alpha}.eval(wo, wi),
                           dielectric * 0.75 + Conductor{base, alpha, false}.eval(wo, wi) * 0.25,
                           1e-12);
            }
}

TEST(MetallicRoughness, TheIndexOfRefractionSetsTheDielectricsF0) {
    // ior 2: F0 = (1/3)^2; at normal incidence on a smooth-ish lobe the specular share is F0.
    const Vec3 wo = direction(0), wi = direction(30, 90);
    const double f0 = 1.0 / 9;
    expectNear(MetallicRoughness{Vec3(0), 0, 0.3, 0, 2.0}.eval(wo, wi),
               Conductor{Vec3(f0), 0.3, false}.eval(wo, wi), 1e-12);
}

TEST(MetallicRoughness, AThinWallPassesLightStraightThroughTintedByTheBaseColour) {
    const MetallicRoughness wall{Vec3(0.2, 0.6, 1.0), 0, 0.3, 1.0};  // all transmission
    const Vec3 wo = direction(35);
    Rng rng(5);
    int through = 0;
    for (int k = 0; k < 2000; ++k) {
        std::optional<BsdfSample> s = wall.sample(wo, rng.uniform(), uniform2(rng));
        if (!s || !s->isTransmission()) continue;
        ++through;
        expectNear(s->wi, -wo, 1e-12);
        EXPECT_TRUE(s->isSpecular());
    }
    EXPECT_GT(through, 1500);  // 1 - F_d of the light goes through
    // The transmitted weight's mean is (1 - F_d(cos_o)) times the tint.
    auto e = albedo({wall}, wo, 200000, 3);
    const double m = 1 - wo.z, fd = 0.04 + 0.96 * m * m * m * m * m;
    EXPECT_GT(e[2].mean(), (1 - fd) * 1.0 - 0.01);
    EXPECT_LT(e[0].mean(), e[2].mean());  // tinted: blue passes, red is mostly absorbed
}

// ---- Reciprocity ----

TEST(Reciprocity, ReflectionIsTheSameBothWays) {
    // The compensated conductors too: f_ms is symmetric in cos_o and cos_i.
    std::vector<Bsdf> bsdfs = {{Lambertian{Vec3(0.8)}},
                               {Conductor{Vec3(0.9, 0.5, 0.2), 0.25}},
                               {Conductor{Vec3(1), 0.8}},
                               {Conductor{Vec3(0.95, 0.64, 0.54), 0.05}},
                               {Conductor{Vec3(0.9, 0.5, 0.2), 0.6, false}},
                               {DiffuseSpecular{Vec3(0.3), Vec3(0.6), 0.5}}};
    Rng rng(17);
    for (const Bsdf& b : bsdfs)
        for (int k = 0; k < 1000; ++k) {
            Vec3 wo = direction(89 * rng.uniform(), 360 * rng.uniform());
            Vec3 wi = direction(89 * rng.uniform(), 360 * rng.uniform());
            if (k % 2) wo.z = -wo.z, wi.z = -wi.z;  // both below: two-sided lobes
            Vec3 a = b.eval(wo, wi), c = b.eval(wi, wo);
            ASSERT_GT(a.x, 0);
            EXPECT_NEAR(a.x, c.x, 1e-12 * a.x);
            EXPECT_NEAR(a.z, c.z, 1e-12 * a.z);
            // Nothing crosses an opaque surface.
            EXPECT_EQ(b.eval(wo, Vec3(wi.x, wi.y, -wi.z)), Vec3(0));
            EXPECT_EQ(b.pdf(wo, Vec3(wi.x, wi.y, -wi.z)), 0);
        }
}

// ---- Delta lobes ----

TEST(Conductor, PerfectMirrorReflectsAboutTheNormalWithSchlicksReflectance) {
    Conductor c{Vec3(0.9, 0.5, 0.04), 0};
    for (double theta : {0.0, 30.0, 70.0, 89.0, 110.0}) {
        Vec3 wo = direction(theta);
        std::optional<BsdfSample> s = c.sample(wo, 0.5, {0.3, 0.7});
        ASSERT_TRUE(s);
        EXPECT_TRUE(s->isSpecular());
        EXPECT_FALSE(s->isTransmission());
        EXPECT_NEAR(s->wi.x, -wo.x, 1e-15);
        EXPECT_NEAR(s->wi.y, -wo.y, 1e-15);
        EXPECT_NEAR(s->wi.z, wo.z, 1e-15);
        double m = 1 - std::abs(wo.z);
        double schlickBlue = 0.04 + 0.96 * std::pow(m, 5);
        EXPECT_NEAR(s->weight().z, schlickBlue, 1e-12);
        EXPECT_NEAR(s->weight().x, 0.9 + 0.1 * std::pow(m, 5), 1e-12);
        EXPECT_EQ(c.eval(wo, s->wi), Vec3(0));
        EXPECT_EQ(c.pdf(wo, s->wi), 0);
    }
}

TEST(Dielectric, ReflectsWithTheFresnelProbabilityAndRefractsBySnellsLaw) {
    Dielectric glass{1.5, Vec3(0.9, 0.8, 0.7)};
    for (double theta : {0.0, 20.0, 45.0, 80.0, 160.0, 140.0}) {
        Vec3 wo = direction(theta);
        bool outside = wo.z > 0;
        double nO = outside ? 1 : 1.5, nI = outside ? 1.5 : 1;  // wo's side, the other side
        double r = fresnelDielectric(std::abs(wo.z), nO / nI);
        ASSERT_LT(r, 1) << theta;
        std::optional<BsdfSample> refl = glass.sample(wo, r * 0.999, {});
        std::optional<BsdfSample> refr = glass.sample(wo, r + (1 - r) * 0.001, {});
        ASSERT_TRUE(refl && refr);
        EXPECT_FALSE(refl->isTransmission());
        EXPECT_TRUE(refr->isTransmission() && refr->isSpecular());
        EXPECT_NEAR(refl->pdf, r, 1e-15);
        EXPECT_NEAR(refr->pdf, 1 - r, 1e-15);
        EXPECT_NEAR(refl->wi.z, wo.z, 1e-15);
        // Snell: n sin is conserved, the azimuth turns by half a circle, the side changes.
        double sinO = std::hypot(wo.x, wo.y), sinI = std::hypot(refr->wi.x, refr->wi.y);
        EXPECT_NEAR(nO * sinO, nI * sinI, 1e-12);
        if (sinO > 0) {
            EXPECT_NEAR(dot(Vec3(wo.x, wo.y, 0), refr->wi), -sinO * sinI, 1e-12);
        }
        EXPECT_LT(wo.z * refr->wi.z, 0);
        // Weights: the tint, and through the boundary also the radiance factor (nO / nI)^2.
        EXPECT_NEAR(refl->weight().y, 0.8, 1e-12);
        EXPECT_NEAR(refr->weight().y, 0.8 * (nO / nI) * (nO / nI), 1e-12);
        EXPECT_EQ(glass.eval(wo, refr->wi), Vec3(0));
        EXPECT_EQ(glass.pdf(wo, refr->wi), 0);
    }
}

TEST(Dielectric, BeyondTheCriticalAngleInsideEverythingIsReflected) {
    Dielectric glass{1.5, Vec3(1)};
    double critical = std::asin(1 / 1.5) * 180 / kPi;  // 41.8 degrees
    Vec3 wo = direction(180 - (critical + 1));         // inside, below the surface
    for (double uc : {0.0, 0.5, 0.999999}) {
        std::optional<BsdfSample> s = glass.sample(wo, uc, {});
        ASSERT_TRUE(s);
        EXPECT_FALSE(s->isTransmission());
        EXPECT_NEAR(s->weight().x, 1, 1e-12);
    }
}

// ---- Rough dielectric ----

/// The factor (n_o / n_i)^2 by which a transmission through the boundary of index ratio `eta`
/// (inside over outside) scales radiance, for a viewer at wo.
double radianceFactor(double eta, const Vec3& wo) { return wo.z > 0 ? 1 / (eta * eta) : eta * eta; }

/// Smith's masking G1 for a direction on either side (optics.h's takes the upper side).
double g1EitherSide(double alpha, const Vec3& w) {
    return Ggx{alpha}.g1(Vec3(w.x, w.y, std::abs(w.z)));
}

TEST(RoughDielectric, SampleWeightIsEvalTimesCosineOverPdfAndTintTimesG1) {
    uint64_t seed = 21;
    for (double eta : {1.5, 1.33, 1 / 1.5})
        for (double alpha : {0.05, 0.3, 0.8})
            for (double theta : {0.0, 35.0, 70.0, 89.0, 100.0, 130.0, 160.0}) {
                Dielectric d{eta, Vec3(0.9, 0.8, 0.7), alpha};
                Vec3 wo = direction(theta);
                Rng rng(seed++);
                int reflected = 0, transmitted = 0;
                for (int k = 0; k < 2000; ++k) {
                    double uc = rng.uniform();
                    std::optional<BsdfSample> s = d.sample(wo, uc, uniform2(rng));
                    if (!s) continue;  // shadowed by the microsurface
                    ASSERT_FALSE(s->isSpecular());
                    ASSERT_EQ(s->isTransmission(), wo.z * s->wi.z < 0);
                    (s->isTransmission() ? transmitted : reflected) += 1;
                    double pdf = d.pdf(wo, s->wi);
                    Vec3 f = d.eval(wo, s->wi);
                    ASSERT_GT(pdf, 0);
                    EXPECT_NEAR(s->pdf, pdf, 1e-9 * pdf);
                    Vec3 fromEval = f * (std::abs(s->wi.z) / pdf);
                    for (int c = 0; c < 3; ++c)
                        EXPECT_NEAR(s->weight()[c], fromEval[c], 1e-9 * fromEval[c]);
                    // Walter's estimator through visible normals: the weight is the tint times
                    // G1(wi), and through the boundary also the radiance factor.
                    double expected = 0.8 * g1EitherSide(alpha, s->wi) *
                                      (s->isTransmission() ? radianceFactor(eta, wo) : 1);
                    EXPECT_NEAR(s->weight().y, expected, 1e-9 * expected);
                }
                EXPECT_GT(reflected, 0) << eta << " " << alpha << " " << theta;
                if (std::abs(wo.z) > 0.5) {
                    EXPECT_GT(transmitted, 0) << eta << " " << alpha;
                }
            }
}

// Reciprocity with refraction (Veach's thesis, section 5.2): radiance is not invariant across
// a boundary, L / n^2 is, so the radiance BSDF carries (n_o / n_i)^2 and the quantity that is
// symmetric is f(wo, wi) / n_o^2, with n_o the index on wo's side and n_i on wi's:
//     f(wo, wi) / n_o^2 == f(wi, wo) / n_i^2.
// For reflection n_o = n_i and this is the usual f(wo, wi) == f(wi, wo).
TEST(Reciprocity, RoughDielectricIsSymmetricInFOverTheSquaredIndexOnWosSide) {
    Rng rng(19);
    for (double eta : {1.5, 1.33})
        for (double alpha : {0.1, 0.4, 0.9}) {
            Dielectric d{eta, Vec3(0.9, 0.8, 0.7), alpha};
            auto index = [&](const Vec3& w) { return w.z > 0 ? 1.0 : eta; };
            int reflections = 0, transmissions = 0;
            for (int k = 0; k < 2000; ++k) {
                Vec3 wo = direction(179 * rng.uniform() + 0.5, 360 * rng.uniform());
                Vec3 wi = direction(179 * rng.uniform() + 0.5, 360 * rng.uniform());
                double a = d.eval(wo, wi).y / (index(wo) * index(wo));
                double b = d.eval(wi, wo).y / (index(wi) * index(wi));
                // 1 - F loses digits as F nears 1 (near total internal reflection): tiny values
                // agree to 1e-14 only.
                EXPECT_NEAR(a, b, 1e-9 * std::max(a, b) + 1e-14) << eta << " " << alpha;
                EXPECT_EQ(a > 0, b > 0);
                if (a > 0) (wo.z * wi.z > 0 ? reflections : transmissions) += 1;
                // The densities are not symmetric, but they are zero together.
                EXPECT_EQ(d.pdf(wo, wi) > 0, d.pdf(wi, wo) > 0);
            }
            // Many pairs of directions carry light (GGX normals reach every direction).
            EXPECT_GT(reflections, 500) << eta << " " << alpha;
            EXPECT_GT(transmissions, 200) << eta << " " << alpha;
        }
}

/// The directional albedo of energy for `wo`: the mean sample weight, with transmissions
/// divided by the radiance factor (n_o / n_i)^2, which changes the solid angle the light
/// fills and not its power. Also the largest single weight.
struct EnergyAlbedo {
    test::MeanEstimate mean;
    double largestWeight = 0;
};
EnergyAlbedo energyAlbedo(const Dielectric& d, const Vec3& wo, long n, uint64_t seed) {
    EnergyAlbedo e;
    Rng rng(seed);
    for (long k = 0; k < n; ++k) {
        double uc = rng.uniform();
        std::optional<BsdfSample> s = d.sample(wo, uc, uniform2(rng));
        double w = 0;
        if (s) w = s->weight().x / (s->isTransmission() ? radianceFactor(d.eta, wo) : 1);
        e.mean.add(w);
        e.largestWeight = std::max(e.largestWeight, w);
    }
    return e;
}

// Single scattering loses the light that the microsurface would scatter again: reflections
// below the surface, transmissions back above it, and the masking G1(wi) of the rest (GGX's
// long tails: at alpha 0.3, 8% of the normals seen from above tilt by more than 45 degrees).
// Measured with 200000 samples per case (standard errors 1e-5 to 1e-3), eta 1.5 and 1.33,
// viewer outside (theta 0, 45, 80) and inside (110, 150, 180), the least albedo found:
//     alpha                          0.02     0.1     0.3     0.7     1.0
//     within 45 degrees of normal    0.9996   0.985   0.871   0.591   0.417
//     at any angle                   0.9956   0.936   0.727   0.484   0.387
// The smallest values are for a viewer inside, where many tilted microfacets reflect totally
// and send the light below the surface. The bounds asserted sit just under these.
TEST(WhiteFurnace, RoughDielectricNeverGainsEnergyAndLosesLittleWhenNearlySmooth) {
    struct Bound {
        double alpha;
        double nearNormal;  ///< The least albedo allowed within 45 degrees of the normal.
        double anyAngle;    ///< ... and at any angle.
    };
    uint64_t seed = 31;
    for (Bound b : {Bound{0.02, 0.999, 0.99}, Bound{0.1, 0.98, 0.93}, Bound{0.3, 0.86, 0.72},
                    Bound{0.7, 0.58, 0.48}, Bound{1.0, 0.41, 0.38}})
        for (double eta : {1.5, 1.33})
            for (double theta : {0.0, 45.0, 80.0, 110.0, 150.0, 180.0}) {
                Vec3 wo = direction(theta);
                EnergyAlbedo e = energyAlbedo({eta, Vec3(1), b.alpha}, wo, 200000, seed++);
                std::printf("eta %.2f, alpha %.2f, theta %3.0f: albedo %.5f +- %.5f\n", eta,
                            b.alpha, theta, e.mean.mean(), e.mean.standardError());
                // Every sample's energy weight is G1(wi) <= 1, so the mean cannot exceed 1.
                EXPECT_LE(e.largestWeight, 1 + 1e-12) << eta << " " << b.alpha << " " << theta;
                double lowest =
                    std::abs(wo.z) >= std::cos(kPi / 4) - 1e-12 ? b.nearNormal : b.anyAngle;
                EXPECT_GE(e.mean.mean() + 4 * e.mean.standardError(), lowest)
                    << eta << " " << b.alpha << " " << theta;
            }
}

TEST(RoughDielectric, ApproachesTheSmoothBoundaryAsAlphaGoesToZero) {
    // At alpha 1e-6 the microfacets tilt by about 1e-6 radians (more than 2.5e-3 with
    // probability (1e-6 / 2.5e-3)^2, GGX's tail): the lobes collapse onto the mirror and Snell
    // directions, with the smooth boundary's Fresnel split and weights.
    Rng rng(23);
    for (double eta : {1.5, 1.33})
        for (double theta : {0.0, 30.0, 75.0, 150.0, 120.0}) {  // 120: total internal reflection
            Dielectric rough{eta, Vec3(0.9, 0.8, 0.7), 1e-6}, smooth{eta, Vec3(0.9, 0.8, 0.7)};
            Vec3 wo = direction(theta);
            double r = fresnelDielectric(std::abs(wo.z), wo.z > 0 ? 1 / eta : eta);
            const int n = 20000;
            int reflections = 0;
            for (int k = 0; k < n; ++k) {
                double uc = rng.uniform();
                Point2 u = uniform2(rng);
                std::optional<BsdfSample> s = rough.sample(wo, uc, u), t = smooth.sample(wo, uc, u);
                ASSERT_TRUE(s && t);
                reflections += !s->isTransmission();
                if (s->isTransmission() != t->isTransmission()) continue;  // uc near R
                EXPECT_NEAR(length(s->wi - t->wi), 0, 5e-3) << eta << " " << theta;
                EXPECT_NEAR(s->weight().y, t->weight().y, 1e-6) << eta << " " << theta;
            }
            double share = static_cast<double>(reflections) / n;
            EXPECT_NEAR(share, r, 4 * std::sqrt(r * (1 - r) / n) + 1e-3) << eta << " " << theta;
            if (r == 1) {
                EXPECT_EQ(reflections, n);  // total internal reflection: no microfacet transmits
            }
        }
}

TEST(RoughDielectric, AnIndexMatchedBoundaryPassesLightStraightThrough) {
    // Nothing bends where the indices match, however rough the interface: the smooth lobe.
    Dielectric matched{1, Vec3(0.5), 0.6};
    for (double theta : {0.0, 40.0, 140.0}) {
        Vec3 wo = direction(theta);
        std::optional<BsdfSample> s = matched.sample(wo, 0.3, {0.2, 0.9});
        ASSERT_TRUE(s);
        EXPECT_TRUE(s->isTransmission() && s->isSpecular());
        EXPECT_NEAR(length(s->wi + wo), 0, 1e-12);
        EXPECT_NEAR(s->weight().x, 0.5, 1e-12);
        EXPECT_EQ(matched.eval(wo, s->wi), Vec3(0));
        EXPECT_EQ(matched.pdf(wo, s->wi), 0);
    }
}

// ---- The course's material ----

TEST(BsdfFromMaterial, PicksTheLobesAndNeverLetsTheColoursSumAboveOne) {
    Material m;
    m.diffuse = {0.5, 1.5, -1};
    Bsdf b = bsdfFromMaterial(m);
    ASSERT_TRUE(b.as<Lambertian>()) << b;
    EXPECT_EQ(b.as<Lambertian>()->albedo, Vec3(0.5, 1, 0));

    m.diffuse = {0.8, 0.2, 0};
    m.specular = {0.6, 0.2, 0.5};
    m.roughness = 0.3;
    b = bsdfFromMaterial(m);
    ASSERT_TRUE(b.as<DiffuseSpecular>()) << b;
    const auto& ds = *b.as<DiffuseSpecular>();
    EXPECT_NEAR(ds.diffuse.x, 0.8 / 1.4, 1e-15);  // 0.8 + 0.6 > 1: both scaled
    EXPECT_NEAR(ds.specular.x, 0.6 / 1.4, 1e-15);
    EXPECT_EQ(ds.diffuse.y, 0.2);  // 0.2 + 0.2 <= 1: kept
    EXPECT_EQ(ds.specular.z, 0.5);
    EXPECT_EQ(ds.alpha, 0.3);

    m.transmission = {1, 0.9, 2};
    m.ior = 1.33;
    b = bsdfFromMaterial(m);
    ASSERT_TRUE(b.as<Dielectric>()) << b;
    EXPECT_EQ(b.as<Dielectric>()->eta, 1.33);
    EXPECT_EQ(b.as<Dielectric>()->tint, Vec3(1, 0.9, 1));
    EXPECT_EQ(b.as<Dielectric>()->alpha, 0.3);  // rough glass
}

}  // namespace
}  // namespace glint
