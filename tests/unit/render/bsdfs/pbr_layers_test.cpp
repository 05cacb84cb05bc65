// glTF's layered BSDF (bsdf.h's MetallicRoughness with the material extensions): sample()
// against pdf() by chi-square tests for every layer and their combination, white furnaces of
// each layer, the sheen's albedo table against quadrature, the thin film against its limits,
// the anisotropic GGX's normalisation, and each extension's effect where it has an exact form.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "glint/render/bsdfs/bsdf.h"
#include "glint/render/bsdfs/ggx_albedo.h"
#include "glint/render/bsdfs/optics.h"
#include "glint/render/bsdfs/sheen.h"
#include "glint/render/bsdfs/thin_film.h"
#include "unit/render/bsdfs/bsdf_checks.h"
#include "unit/statistics.h"
#include "unit/test_support.h"

namespace glint {
namespace {

using test::direction;

/// A dielectric of base colour `base` without its specular reflection (KHR_materials_specular
/// 0): a Lambertian lobe alone, so that a layer's furnace shows only the layer's share.
MetallicRoughness diffuseOnly(const Vec3& base) {
    MetallicRoughness m{base, 0, 0.5};
    m.specular = 0;
    return m;
}

MetallicRoughness coated(MetallicRoughness m, double weight, double alpha,
                         Vec3 normal = {0, 0, 1}) {
    m.coat = {weight, alpha, normalize(normal)};
    return m;
}

MetallicRoughness sheened(MetallicRoughness m, const Vec3& colour, double alpha) {
    m.sheen = {colour, alpha};
    return m;
}

struct LayerCase {
    std::string name;
    MetallicRoughness bsdf;
    Vec3 wo;
};

std::vector<LayerCase> layerCases() {
    std::vector<LayerCase> cases;
    const MetallicRoughness red{Vec3(0.8, 0.1, 0.1), 0, 0.4};
    auto add = [&](const std::string& name, const MetallicRoughness& m) {
        for (double theta : {20.0, 70.0, 130.0})
            cases.push_back({name + "_" + std::to_string(int(theta)), m, direction(theta)});
    };
    add("coat_smooth", coated(red, 1, 0.01));
    add("coat_rough", coated(red, 0.6, 0.3));
    add("coat_tilted", coated(red, 1, 0.05, {0.3, -0.2, 1}));
    add("coat_on_metal", coated(MetallicRoughness{Vec3(0.9, 0.7, 0.3), 1, 0.2}, 1, 0.02));
    add("sheen_soft", sheened(red, Vec3(1, 0.9, 0.8), 0.3));
    add("sheen_sharp", sheened(red, Vec3(0.5), 0.05));
    MetallicRoughness specular = red;
    specular.specular = 0.6;
    specular.specularColor = Vec3(2, 1, 0.2);
    add("specular_colour", specular);
    MetallicRoughness aniso{Vec3(0.9), 1, 0.05};
    aniso.anisotropy = 0.8;
    add("anisotropic_metal", aniso);
    MetallicRoughness film = red;
    film.iridescence = {1, 1.3, 450};
    add("iridescent", film);
    MetallicRoughness leaf{Vec3(0.2, 0.7, 0.1), 0, 0.5};
    leaf.diffuseTransmission = 0.6;
    leaf.diffuseTransmissionColor = Vec3(0.9, 1, 0.4);
    add("diffuse_transmission", leaf);
    MetallicRoughness all = sheened(coated(leaf, 0.7, 0.1, {-0.2, 0.1, 1}), Vec3(0.4), 0.5);
    all.anisotropy = 0.5;
    all.iridescence = {0.5, 1.4, 300};
    all.transmission = 0.3;
    add("everything", all);
    MetallicRoughness glass = coated(MetallicRoughness{Vec3(1), 0, 0.1, 1, 1.5, false}, 1, 0.05);
    add("coated_rough_glass", glass);
    return cases;
}

void PrintTo(const LayerCase& c, std::ostream* os) { *os << c.name; }

class LayerChiSquare : public testing::TestWithParam<LayerCase> {};

TEST_P(LayerChiSquare, SampledDirectionsFollowThePdf) {
    const LayerCase& c = GetParam();
    const double level = test::sidak(test::kAlpha, static_cast<int>(layerCases().size()));
    const Bsdf bsdf{c.bsdf};
    const uint64_t seed = std::hash<std::string>{}(c.name) % 100000;
    test::ChiSquareRun run = test::chiSquare(bsdf, bsdf, c.wo, seed);
    std::printf("%s: chi2 %.1f, %d dof, p-value %.4f\n", c.name.c_str(), run.result.chi2,
                run.result.dof, run.result.pValue);
    EXPECT_FALSE(run.result.outsideSupport) << c.name;
    EXPECT_GT(run.result.pValue, level) << c.name << ": chi2 " << run.result.chi2;
    EXPECT_LT(run.worstMismatch, 1e-9) << c.name;
}

INSTANTIATE_TEST_SUITE_P(PbrLayers, LayerChiSquare, testing::ValuesIn(layerCases()),
                         [](const testing::TestParamInfo<LayerCase>& p) { return p.param.name; });

TEST(LayerChiSquarePower, ADensityThatForgetsALayerIsRejected) {
    // The same BSDF's pdf without its coat: the coat's samples land where it says nothing.
    const MetallicRoughness with = coated(MetallicRoughness{Vec3(0.8, 0.1, 0.1), 0, 0.6}, 1, 0.05);
    MetallicRoughness without = with;
    without.coat.weight = 0;
    const Bsdf a{with}, b{without};
    test::ChiSquareRun run = test::chiSquare(a, b, direction(50), 5);
    EXPECT_LT(run.result.pValue, 1e-6);
}

// ---- White furnaces ----

/// The mean of each channel's directional albedo estimate, and its standard error.
struct Albedo {
    Vec3 mean, error;
};
Albedo albedoOf(const MetallicRoughness& m, const Vec3& wo, long n = 200000) {
    auto e = test::albedo(Bsdf{m}, wo, n, 17);
    return {{e[0].mean(), e[1].mean(), e[2].mean()},
            {e[0].standardError(), e[1].standardError(), e[2].standardError()}};
}

TEST(PbrLayersFurnace, ASmoothClearcoatOverAWhiteBaseReflectsEverything) {
    // The coat reflects w F_c (its GGX loses nothing when smooth), the base the rest.
    for (double theta : {0.0, 40.0, 75.0}) {
        Albedo a = albedoOf(coated(diffuseOnly(Vec3(1)), 1, 0.01), direction(theta));
        EXPECT_NEAR(a.mean.x, 1, 4 * a.error.x + 2e-3) << theta;
    }
    // A rough coat loses what its single scattering loses: 1 - w F_c (1 - E(cos_o)).
    const Vec3 wo = direction(70);
    Albedo rough = albedoOf(coated(diffuseOnly(Vec3(1)), 1, 0.8), wo);
    const double m = 1 - wo.z, fc = 0.04 + 0.96 * m * m * m * m * m;
    EXPECT_NEAR(rough.mean.x, 1 - fc * (1 - GgxAlbedo(0.8)(wo.z)),
                4 * rough.error.x + ggx_albedo_table::kMaxError);
}

TEST(PbrLayersFurnace, TheCoatDimsTheBaseByWhatItReflects) {
    // A black base under a coat reflects the coat's Schlick reflectance at the normal's cosine.
    for (double theta : {0.0, 60.0, 80.0}) {
        const Vec3 wo = direction(theta);
        Albedo a = albedoOf(coated(diffuseOnly(Vec3(0)), 0.5, 0.01), wo);
        const double m = 1 - wo.z, schlick = 0.04 + 0.96 * m * m * m * m * m;
        EXPECT_NEAR(a.mean.x, 0.5 * schlick, 4 * a.error.x + 2e-3) << theta;
    }
}

TEST(PbrLayersFurnace, SheenTakesFromTheBaseWhatItReflects) {
    for (double alpha : {0.05, 0.3, 1.0})
        for (double theta : {10.0, 50.0, 80.0}) {
            const Vec3 wo = direction(theta);
            Albedo a = albedoOf(sheened(diffuseOnly(Vec3(1)), Vec3(1), alpha), wo);
            EXPECT_LE(a.mean.x, 1 + 4 * a.error.x) << alpha << " " << theta;
            // White sheen over a white base: the sheen's albedo plus the scaled base.
            EXPECT_GT(a.mean.x, 0.85) << alpha << " " << theta;
            // A black base shows the sheen's albedo alone.
            Albedo s = albedoOf(sheened(diffuseOnly(Vec3(0)), Vec3(1), alpha), wo);
            EXPECT_NEAR(s.mean.x, sheenAlbedoByQuadrature(alpha, wo.z, 200), 4 * s.error.x)
                << alpha << " " << theta;
        }
}

TEST(PbrLayersFurnace, DiffuseTransmissionSendsItsShareThrough) {
    MetallicRoughness m = diffuseOnly(Vec3(1));
    m.diffuseTransmission = 0.7;
    m.diffuseTransmissionColor = Vec3(1, 0.5, 0);
    const Vec3 wo = direction(30);
    auto through = test::albedo(Bsdf{m}, wo, 200000, 3);
    // Split by side (each sample counts on both, as 0 on the side it did not go to):
    // reflection albedo 0.3, transmission 0.7 times the colour.
    Rng rng(9);
    test::MeanEstimate reflected, transmitted;
    for (long k = 0; k < 200000; ++k) {
        double uc = rng.uniform();
        auto s = Bsdf{m}.sample(wo, uc, test::uniform2(rng));
        double w = s ? s->weight().x : 0;
        (s && s->wi.z > 0 ? reflected : transmitted).add(w);
        (s && s->wi.z > 0 ? transmitted : reflected).add(0);
    }
    EXPECT_NEAR(reflected.mean(), 0.3, 0.01);
    EXPECT_NEAR(transmitted.mean(), 0.7, 0.01);
    EXPECT_NEAR(through[1].mean(), 0.3 + 0.7 * 0.5, 0.01);
    EXPECT_NEAR(through[2].mean(), 0.3, 0.01);
}

TEST(PbrLayersFurnace, NoLayeredBsdfReflectsMoreThanItReceives) {
    for (const LayerCase& c : layerCases()) {
        if (std::abs(c.wo.z) < 0.5) continue;  // the specification's base gains near grazing
        // A viewer inside glass sees the outside's radiance scaled up by eta^2.
        if (c.wo.z < 0 && !c.bsdf.thin && c.bsdf.transmission > 0) continue;
        Albedo a = albedoOf(c.bsdf, c.wo, 100000);
        for (int k = 0; k < 3; ++k) EXPECT_LE(a.mean[k], 1 + 4 * a.error[k] + 1e-3) << c.name;
    }
}

// ---- The parts ----

TEST(Sheen, TheCommittedAlbedoTableIsTheQuadratureItSaysItIs) {
    // tools/sheen_albedo_table.cpp wrote sheen_albedo_table.cpp: every entry again, here.
    using namespace sheen_albedo_table;
    for (int r = 0; r < kRows; ++r)
        for (int c = 0; c < kColumns; ++c) {
            const double e = sheenAlbedoByQuadrature(rowAlpha(r), columnMu(c), kSteps);
            ASSERT_NEAR(kE[r * kColumns + c], e, 1e-6 * std::max(1.0, e))
                << "row " << r << ", column " << c << ": run tools/sheen_albedo_table.cpp";
        }
    // The lookup returns the entries at the nodes.
    EXPECT_NEAR(sheenAlbedo(rowAlpha(5), columnMu(7)), kE[5 * kColumns + 7], 1e-6);
}

TEST(Sheen, TheAlbedoTableAgreesWithQuadratureAndTheLobeIsReciprocal) {
    for (double alpha : {kMinSheenAlpha, 0.02, 0.11, 0.37, 0.8, 1.0})
        for (double mu : {0.05, 0.2, 0.5, 0.77, 1.0}) {
            const double exact = sheenAlbedoByQuadrature(alpha, mu, 200);
            EXPECT_NEAR(sheenAlbedo(alpha, mu), exact, 0.025) << alpha << " " << mu;
            EXPECT_GE(exact, 0);
            // The fitted masking term lets the smoothest sheens reflect up to 8% more than
            // they receive at grazing angles (docs/materials.md): bounded, never runaway.
            EXPECT_LT(exact, alpha < 0.01 && mu < 0.1 ? 1.1 : 1.0) << alpha << " " << mu;
        }
    const Vec3 o = direction(35), i = direction(70, 200);
    EXPECT_DOUBLE_EQ(sheenLobe(0.3, o, i), sheenLobe(0.3, i, o));
    EXPECT_EQ(sheenLobe(0.3, o, Vec3(0, 0, -1)), 0);
}

TEST(ThinFilm, NoFilmIsTheBasesSchlickReflectanceAndFilmsAverageToTheIncoherentSum) {
    // The specification's film of thickness 0 has index 1: at normal incidence only the base
    // reflects (away from it, its first interface keeps Schlick's (1 - c)^5 of f0 = 0).
    const Vec3 f0(0.04, 0.2, 0.9);
    const Vec3 bare = thinFilmReflectance(1, 1.3, 0, f0);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(bare[k], f0[k], 0.01);
    // Over many thicknesses the interference averages out: the mean is the incoherent sum of
    // the two interfaces' reflections, R12 + T^2 R23 / (1 - R12 R23).
    const double film = 1.33, base = 1.6, c = 1;
    auto fresnel0 = [](double a, double b) { return (a - b) * (a - b) / ((a + b) * (a + b)); };
    const double r12 = fresnel0(film, 1), r23 = fresnel0(base, film);
    const double incoherent = r12 + (1 - r12) * (1 - r12) * r23 / (1 - r12 * r23);
    const double baseF0 = fresnel0(base, 1);
    Vec3 sum(0);
    const int n = 2000;
    for (int k = 0; k < n; ++k) sum += thinFilmReflectance(c, film, 300 + 2.0 * k, Vec3(baseF0));
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(sum[k] / n, incoherent, 0.004);
    // A thin film colours: a 300 nm film of index 1.33 reflects its channels differently.
    const Vec3 colour = thinFilmReflectance(1, film, 300, Vec3(baseF0));
    EXPECT_GT(std::max({colour.x, colour.y, colour.z}) - std::min({colour.x, colour.y, colour.z}),
              0.02);
}

TEST(AnisotropicGgx, ProjectedMicrofacetAreaIsOneAndIsotropyIsTheOldLobe) {
    for (auto [ax, ay] : {std::pair{0.1, 0.4}, std::pair{0.6, 0.2}, std::pair{0.3, 0.3}}) {
        const Ggx ggx{ax, ay};
        // Integral of D(h) cos_h over the hemisphere, in (cos theta, phi).
        auto overPhi = [&](double ct) {
            const double st = std::sqrt(std::max(0.0, 1 - ct * ct));
            return test::integrate(
                [&](double phi) {
                    return ggx.d(Vec3(st * std::cos(phi), st * std::sin(phi), ct)) * ct;
                },
                0, 2 * test::kPi, 1e-9);
        };
        EXPECT_NEAR(test::integrate(overPhi, 0, 1, 1e-8), 1, 2e-3) << ax << " " << ay;
    }
    const Ggx iso{0.3}, same{0.3, 0.3};
    const Vec3 h = normalize(Vec3(0.2, -0.1, 0.9)), v = direction(60);
    EXPECT_DOUBLE_EQ(iso.d(h), same.d(h));
    EXPECT_NEAR(Ggx(0.3, 0.3 + 1e-12).d(h), iso.d(h), 1e-9);
    EXPECT_NEAR(Ggx(0.3, 0.3 + 1e-12).g1(v), iso.g1(v), 1e-9);
}

TEST(Anisotropy, StretchesTheHighlightAlongTheTangent) {
    MetallicRoughness m{Vec3(1), 1, 0.05};
    m.anisotropy = 0.7;
    const Vec3 wo(0, 0, 1);
    // Off the mirror direction by the same angle along x (the tangent) and along y.
    const Vec3 alongX = direction(20, 0), alongY = direction(20, 90);
    EXPECT_GT(m.eval(wo, alongX).x, 20 * m.eval(wo, alongY).x);
    m.anisotropy = 0;
    EXPECT_NEAR(m.eval(wo, alongX).x, m.eval(wo, alongY).x, 1e-12);
}

TEST(Specular, TheFactorAndColourSetTheDielectricsReflectance) {
    const Vec3 wo(0, 0, 1), wi = wo;  // h = n: Fresnel is f0 itself
    MetallicRoughness plain{Vec3(0), 0, 0.2};
    MetallicRoughness none = plain;
    none.specular = 0;
    EXPECT_EQ(none.eval(wo, wi), Vec3(0));  // black base, no specular: nothing
    MetallicRoughness coloured = plain;
    coloured.specularColor = Vec3(1, 0.5, 0);
    // 0.04 times the colour.
    const Vec3 f = coloured.eval(wo, wi), g = plain.eval(wo, wi);
    EXPECT_NEAR(f.x / g.x, 1, 1e-12);
    EXPECT_NEAR(f.y / g.y, 0.5, 1e-12);
    EXPECT_NEAR(f.z, 0, 1e-15);
}

}  // namespace
}  // namespace glint

namespace glint {
namespace {

TEST(Dispersion, TheIndexFollowsTheCauchyFitThroughTheBaseIndex) {
    MetallicRoughness glass{Vec3(1), 0, 0.01, 1, 1.5, false};
    EXPECT_FALSE(glass.disperses());
    for (int c = 0; c < 3; ++c) EXPECT_EQ(glass.etaOfChannel(c), 1.5);
    glass.dispersion = 20.0 / 30;  // Abbe number 30, a flint glass
    EXPECT_TRUE(glass.disperses());
    const double r = glass.etaOfChannel(0), g = glass.etaOfChannel(1), b = glass.etaOfChannel(2);
    EXPECT_LT(r, g);  // normal dispersion: shorter wavelengths bend more
    EXPECT_LT(g, b);
    // Abbe's number is (n_d - 1) / (n_F - n_C), the spread between 486.1 and 656.3 nm; the
    // blue and red channels (465 and 610 nm) spread about as much.
    EXPECT_GT(b - r, 0.9 * 0.5 / 30);
    EXPECT_LT(b - r, 1.1 * 0.5 / 30);
    EXPECT_NEAR(g, 1.5, 0.005);  // 550 nm is near the fit's anchor, n_d at 587.6 nm
    glass.thin = true;           // a thin wall does not refract: nothing to disperse
    EXPECT_FALSE(glass.disperses());
}

}  // namespace
}  // namespace glint
