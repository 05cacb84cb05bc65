// What integrators ask a BSDF instead of its lobe's type (bsdf.h): what it can scatter, the
// index of the volume it bounds, dispersion, the render passes' albedo, whether it casts
// caustics; and how it prints itself.

#include <gtest/gtest.h>

#include <optional>
#include <sstream>
#include <string>

#include "glint/render/bsdfs/bsdf.h"
#include "unit/render/bsdfs/bsdf_checks.h"

namespace glint {
namespace {

using enum BsdfFlags;

template <typename T>
std::string print(const T& value) {
    std::ostringstream out;
    out << value;
    return out.str();
}

TEST(BsdfQuestions, FlagsSayWhatEachLobeCanScatter) {
    EXPECT_EQ(Bsdf(Lambertian{Vec3(0.5)}).flags(), Reflection | Diffuse);
    EXPECT_EQ(Bsdf(Conductor{Vec3(1), 0}).flags(), Reflection | Specular);
    EXPECT_EQ(Bsdf(Conductor{Vec3(1), 0.2}).flags(), Reflection | Glossy);
    EXPECT_EQ(Bsdf(Dielectric{1.5, Vec3(1), 0}).flags(), Reflection | Transmission | Specular);
    EXPECT_EQ(Bsdf(Dielectric{1.5, Vec3(1), 0.2}).flags(), Reflection | Transmission | Glossy);
    // An index-matched boundary bends nothing: a delta, whatever its roughness.
    EXPECT_EQ(Bsdf(Dielectric{1, Vec3(1), 0.2}).flags(), Reflection | Transmission | Specular);
    EXPECT_EQ(Bsdf(DiffuseSpecular{Vec3(0.5), Vec3(0.5), 0}).flags(),
              Reflection | Diffuse | Specular);
    EXPECT_EQ(Bsdf(DiffuseSpecular{Vec3(0), Vec3(0.5), 0.1}).flags(), Reflection | Glossy);
    const MetallicRoughness plastic{Vec3(0.5), 0, 0.3};
    EXPECT_EQ(Bsdf(plastic).flags(), Reflection | Diffuse | Glossy);
    const MetallicRoughness metal{Vec3(0.9), 1, 0.3};
    EXPECT_EQ(Bsdf(metal).flags(), Reflection | Glossy);
    const MetallicRoughness glass{Vec3(1), 0, 0.01, 1, 1.5, false};
    EXPECT_EQ(Bsdf(glass).flags(), Reflection | Glossy | Transmission);
    const MetallicRoughness thin{Vec3(1), 0, 0.01, 1, 1.5, true};
    EXPECT_EQ(Bsdf(thin).flags(), Reflection | Glossy | Transmission | Specular);
    MetallicRoughness leaf{Vec3(0.3, 0.6, 0.2), 0, 0.5};
    leaf.diffuseTransmission = 0.5;
    EXPECT_EQ(Bsdf(leaf).flags(), Reflection | Diffuse | Glossy | Transmission);
}

TEST(BsdfQuestions, SpecularOnlyAndTransmitsFollowFromTheFlags) {
    EXPECT_TRUE(Bsdf(Conductor{Vec3(1), 0}).specularOnly());
    EXPECT_TRUE(Bsdf(Dielectric{1.5, Vec3(1), 0}).specularOnly());
    EXPECT_TRUE(Bsdf(DiffuseSpecular{Vec3(0), Vec3(1), 0}).specularOnly());
    EXPECT_FALSE(Bsdf(DiffuseSpecular{Vec3(0.1), Vec3(0.9), 0}).specularOnly());
    EXPECT_FALSE(Bsdf(Dielectric{1.5, Vec3(1), 0.1}).specularOnly());
    EXPECT_FALSE(Bsdf(MetallicRoughness{Vec3(1), 1, MetallicRoughness::kMinAlpha}).specularOnly());
    EXPECT_TRUE(Bsdf(Dielectric{1.5, Vec3(1), 0}).transmits());
    EXPECT_FALSE(Bsdf(Conductor{Vec3(1), 0}).transmits());
    MetallicRoughness leaf{Vec3(0.5), 0, 0.5};
    EXPECT_FALSE(Bsdf(leaf).transmits());
    leaf.diffuseTransmission = 0.2;
    EXPECT_TRUE(Bsdf(leaf).transmits());
}

TEST(BsdfQuestions, OnlyLobesThatRefractIntoAVolumeHaveARelativeIndex) {
    EXPECT_EQ(Bsdf(Dielectric{1.33, Vec3(1), 0}).relativeEta(), 1.33);
    EXPECT_EQ(Bsdf(Dielectric{1, Vec3(1), 0}).relativeEta(), 1.0);  // still a boundary
    EXPECT_EQ(Bsdf(Lambertian{Vec3(1)}).relativeEta(), std::nullopt);
    EXPECT_EQ(Bsdf(Conductor{Vec3(1), 0}).relativeEta(), std::nullopt);
    EXPECT_EQ(Bsdf(DiffuseSpecular{Vec3(0.5), Vec3(0.5), 0}).relativeEta(), std::nullopt);
    const MetallicRoughness volume{Vec3(1), 0, 0.1, 1, 1.45, false};
    EXPECT_EQ(Bsdf(volume).relativeEta(), 1.45);
    const MetallicRoughness thin{Vec3(1), 0, 0.1, 1, 1.45, true};
    EXPECT_EQ(Bsdf(thin).relativeEta(), std::nullopt);  // a thin wall bends nothing
    const MetallicRoughness opaque{Vec3(1), 0, 0.1, 0, 1.45, false};
    EXPECT_EQ(Bsdf(opaque).relativeEta(), std::nullopt);
}

TEST(BsdfQuestions, ADispersingVolumeTakesTheIndexOfTheChannelChosen) {
    MetallicRoughness prism{Vec3(1), 0, 0.01, 1, 1.5, false};
    prism.dispersion = 0.5;
    Bsdf b = prism;
    ASSERT_TRUE(b.disperses());
    b.selectChannel(2);  // blue bends most
    EXPECT_EQ(b.relativeEta(), prism.etaOfChannel(2));
    EXPECT_GT(*b.relativeEta(), 1.5);
    Bsdf red = prism;
    red.selectChannel(0);
    EXPECT_LT(*red.relativeEta(), 1.5);
    // A thin wall, or glass without dispersion, stays as it was.
    MetallicRoughness thin = prism;
    thin.thin = true;
    Bsdf t = thin;
    EXPECT_FALSE(t.disperses());
    t.selectChannel(2);
    EXPECT_EQ(t.as<MetallicRoughness>()->eta, 1.5);
    Bsdf glass = Dielectric{1.5, Vec3(1), 0};
    EXPECT_FALSE(glass.disperses());
    glass.selectChannel(2);
    EXPECT_EQ(glass.relativeEta(), 1.5);
}

TEST(BsdfQuestions, ThePassesLookThroughMirrorsAndSmoothGlassOnly) {
    EXPECT_EQ(Bsdf(Lambertian{Vec3(0.2, 0.4, 0.6)}).passAlbedo(), Vec3(0.2, 0.4, 0.6));
    EXPECT_EQ(Bsdf(Conductor{Vec3(0.9), 0}).passAlbedo(), std::nullopt);
    EXPECT_EQ(Bsdf(Conductor{Vec3(0.9), 0.1}).passAlbedo(), Vec3(0.9));
    EXPECT_EQ(Bsdf(Dielectric{1.5, Vec3(0.8), 0}).passAlbedo(), std::nullopt);
    EXPECT_EQ(Bsdf(Dielectric{1.5, Vec3(0.8), 0.2}).passAlbedo(), Vec3(0.8));
    EXPECT_EQ(Bsdf(DiffuseSpecular{Vec3(0), Vec3(0.8), 0}).passAlbedo(), std::nullopt);
    EXPECT_EQ(Bsdf(DiffuseSpecular{Vec3(0.5), Vec3(0.7), 0}).passAlbedo(), Vec3(1));
    const MetallicRoughness chrome{Vec3(0.9), 1, MetallicRoughness::kMinAlpha};
    EXPECT_EQ(Bsdf(chrome).passAlbedo(), std::nullopt);
    const MetallicRoughness brushed{Vec3(0.9), 1, 0.04};
    EXPECT_EQ(Bsdf(brushed).passAlbedo(), Vec3(0.9));
    const MetallicRoughness paint{Vec3(0.1, 0.2, 0.3), 0, MetallicRoughness::kMinAlpha};
    EXPECT_EQ(Bsdf(paint).passAlbedo(), Vec3(0.1, 0.2, 0.3));
}

TEST(BsdfQuestions, SmoothOrGlossyMirrorsMetalsAndGlassCastCaustics) {
    EXPECT_FALSE(Bsdf(Lambertian{Vec3(1)}).castsCaustics());
    EXPECT_TRUE(Bsdf(Conductor{Vec3(1), 0.05}).castsCaustics());
    EXPECT_FALSE(Bsdf(Conductor{Vec3(1), 0.3}).castsCaustics());
    EXPECT_TRUE(Bsdf(Dielectric{1.5, Vec3(1), 0}).castsCaustics());
    EXPECT_FALSE(Bsdf(Dielectric{1.5, Vec3(1), kCausticAlpha}).castsCaustics());
    EXPECT_TRUE(Bsdf(DiffuseSpecular{Vec3(0), Vec3(0.9), 0}).castsCaustics());
    EXPECT_FALSE(Bsdf(DiffuseSpecular{Vec3(0.1), Vec3(0.9), 0}).castsCaustics());
    EXPECT_FALSE(Bsdf(DiffuseSpecular{Vec3(0), Vec3(0), 0}).castsCaustics());  // black
    const MetallicRoughness gold{Vec3(1, 0.8, 0.3), 1, 0.04};
    EXPECT_TRUE(Bsdf(gold).castsCaustics());
    const MetallicRoughness mostlyMetal{Vec3(1), 0.98, 0.04};
    EXPECT_FALSE(Bsdf(mostlyMetal).castsCaustics());  // 2% diffuse
    const MetallicRoughness glass{Vec3(1), 0, 0.01, 1, 1.5, false};
    EXPECT_TRUE(Bsdf(glass).castsCaustics());
}

TEST(BsdfPrinting, EachLobeSaysWhatItIs) {
    EXPECT_EQ(print(Bsdf(Lambertian{Vec3(0.5, 0.25, 1)})), "Lambertian{albedo (0.5, 0.25, 1)}");
    EXPECT_EQ(print(Bsdf(Dielectric{1.5, Vec3(1), 0.2})),
              "Dielectric{eta 1.5, tint (1, 1, 1), alpha 0.2}");
    EXPECT_EQ(print(Bsdf(Conductor{Vec3(0.9), 0, false})),
              "Conductor{f0 (0.9, 0.9, 0.9), alpha 0, single scattering}");
    EXPECT_EQ(print(Bsdf(DiffuseSpecular{Vec3(0.5), Vec3(0.25), 0})),
              "DiffuseSpecular{diffuse (0.5, 0.5, 0.5), specular (0.25, 0.25, 0.25), alpha 0}");
    MetallicRoughness m{Vec3(1, 0, 0), 0.5, 0.25};
    m.coat.weight = 0.5;
    EXPECT_EQ(print(Bsdf(m)),
              "MetallicRoughness{baseColor (1, 0, 0), metallic 0.5, alpha 0.25, transmission 0, "
              "eta 1.5, thin, coat 0.5}");
    EXPECT_EQ(print(Reflection | Transmission | Glossy), "Reflection | Transmission | Glossy");
    EXPECT_EQ(print(BsdfFlags::None), "None");
    EXPECT_EQ(print(BsdfSample{Vec3(0, 0, 1), Vec3(0.5), 0.25, Reflection | Specular}),
              "BsdfSample{wi (0, 0, 1), f (0.5, 0.5, 0.5), pdf 0.25, Reflection | Specular}");
}

}  // namespace
}  // namespace glint
