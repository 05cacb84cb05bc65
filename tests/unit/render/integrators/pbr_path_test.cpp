// glTF's metallic-roughness materials (scene/pbr_material.h) as the path tracer renders them:
// per-texel base colour on metal, double-sided and single-sided faces, normal maps, alpha
// masks and blending, emissive textures as lights. Each scene is a unit quad in the z = 0
// plane built here; estimates are means of many samples with their standard errors.

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>

#include "glint/render/integrators/path.h"
#include "glint/scene/pbr_material.h"
#include "unit/statistics.h"

namespace glint {
namespace {

constexpr double kZ = 5;

/// A width x height sRGB-free (linear) image from a function of the texel.
template <typename F>
std::shared_ptr<TextureImage> image(int width, int height, F texel, bool withAlpha = false) {
    auto img = std::make_shared<TextureImage>();
    img->width = width;
    img->height = height;
    img->srgb = false;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            std::array<uint8_t, 4> t = texel(x, y);
            for (size_t k = 0; k < 3; ++k) img->rgb.push_back(t[k]);
            if (withAlpha) img->alpha.push_back(t[3]);
        }
    return img;
}

TextureSlot slot(std::shared_ptr<TextureImage> img) {
    TextureSlot s;
    s.image = std::move(img);
    s.wrapS = s.wrapT = TextureWrap::Clamp;
    return s;
}

/// The quad [-1, 1]^2 at z = `z`, facing +z, with u = (x + 1) / 2 and v = (y + 1) / 2.
void addQuad(Scene& scene, uint32_t material, double z = 0) {
    const Vec3 p[4] = {{-1, -1, z}, {1, -1, z}, {1, 1, z}, {-1, 1, z}};
    const TexCoord uv[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    const Vec3 n[3] = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
    const TexCoord a[3] = {uv[0], uv[1], uv[2]}, b[3] = {uv[0], uv[2], uv[3]};
    scene.primitives.addTriangle(p[0], p[1], p[2], n, a, material);
    scene.primitives.addTriangle(p[0], p[2], p[3], n, b, material);
}

uint32_t pbrMaterial(Scene& scene, const PbrMaterial& pm) {
    Material m;
    m.pbr = scene.addPbrMaterial(pm);
    m.emission = pm.emissive;  // the flat material's emission: what the light sampler weighs
    return scene.addMaterial(m);
}

LightSpec directional(const Vec3& towards, double intensity) {
    LightSpec l;
    l.kind = LightSpec::Kind::Directional;
    l.direction = normalize(towards);
    l.color = Vec3(intensity);
    return l;
}

/// Mean radiance (channel c) along `ray` as the renderer computes it: camera hits filtered.
test::MeanEstimate estimate(const Scene& scene, const Ray& ray, int n, int c = 1,
                            PathIntegrator::Strategy strategy = PathIntegrator::Strategy::Mis) {
    PathIntegrator integrator(scene, strategy);
    test::MeanEstimate e;
    for (int i = 0; i < n; ++i) {
        // Vary the origin by a hair so that stochastic (blended) hits differ per sample.
        Ray r = ray;
        r.origin = r.origin + Vec3(1e-9 * i, 0, 0);
        Hit hit;
        bool found = scene.intersect(r, hit, true);
        RayCounts counts;
        PathContext ctx{Rng(7 + i), counts};
        ctx.pixelSeed = 99;
        ctx.sampleIndex = static_cast<uint32_t>(i);
        Vec3 L = integrator.li(r, found ? &hit : nullptr, ctx);
        EXPECT_EQ(counts.nonFinite, 0u);
        e.add(L[c]);
    }
    return e;
}

Ray towards(const Vec3& from, const Vec3& at) {
    return Ray{from, normalize(at - from), 0, kInfinity};
}

TEST(PbrPath, DoubleSidedFacesAreLitAlikeFromBothSidesAndSingleSidedBackFacesAreNotSeen) {
    for (bool doubleSided : {true, false}) {
        auto render = [&](double side) {
            auto scene = std::make_unique<Scene>();
            scene->integrator = "path";
            PbrMaterial pm;
            pm.baseColor = Vec3(0.6);
            pm.metallic = 0;
            pm.roughness = 0.6;
            pm.doubleSided = doubleSided;
            addQuad(*scene, pbrMaterial(*scene, pm));
            scene->lights.push_back(directional({0.3, 0.2, side}, 2));
            scene->background = Background{Vec3(0.25), Vec3(0.25)};
            scene->maxDepth = 1;
            scene->prepare();
            return estimate(*scene, towards({0.4, -0.5, 3 * side}, {0.1, 0.1, 0}), 4000);
        };
        test::MeanEstimate front = render(1), back = render(-1);
        if (doubleSided) {
            EXPECT_GT(front.mean(), 0.3);
            EXPECT_NEAR(back.mean(), front.mean(),
                        kZ * std::hypot(front.standardError(), back.standardError()));
        } else {
            EXPECT_NEAR(back.mean(), 0.25, 1e-12);  // culled: the background shows
            EXPECT_GT(front.mean(), 0.3);
        }
    }
}

TEST(PbrPath, AMetalTakesItsColourFromTheBaseColourTexturePerTexel) {
    auto scene = std::make_unique<Scene>();
    PbrMaterial pm;
    pm.metallic = 1;
    pm.roughness = 0.5;
    pm.baseColorTexture = slot(image(2, 1, [](int x, int) {
        return x == 0 ? std::array<uint8_t, 4>{230, 20, 20, 255}
                      : std::array<uint8_t, 4>{20, 230, 20, 255};
    }));
    addQuad(*scene, pbrMaterial(*scene, pm));
    scene->background = Background{Vec3(1), Vec3(1)};
    scene->maxDepth = 1;
    scene->prepare();
    const Vec3 eye(0, 0, 3);
    auto red = [&](double x) { return estimate(*scene, towards(eye, {x, 0, 0}), 2000, 0).mean(); };
    auto green = [&](double x) {
        return estimate(*scene, towards(eye, {x, 0, 0}), 2000, 1).mean();
    };
    // The left half (u < 0.5) is red metal, the right half green.
    EXPECT_GT(red(-0.6), 3 * green(-0.6));
    EXPECT_GT(green(0.6), 3 * red(0.6));
}

TEST(PbrPath, ANormalMapTurnsTheShadingTowardsAGrazingLight) {
    // A matte quad lit 80 degrees from its normal; the map tilts the normals 45 degrees
    // towards the light, so the cosine goes from cos 80 to about cos 35.
    auto render = [](bool mapped) {
        auto scene = std::make_unique<Scene>();
        PbrMaterial pm;
        pm.baseColor = Vec3(0.8);
        pm.metallic = 0;
        pm.roughness = 1;
        pm.ior = 1;  // no specular layer: Lambert alone
        if (mapped) {
            const double s = std::sin(std::numbers::pi / 4), c = std::cos(std::numbers::pi / 4);
            auto byte = [](double x) { return static_cast<uint8_t>(std::lround((x + 1) * 127.5)); };
            pm.normalTexture = slot(image(1, 1, [&](int, int) {
                return std::array<uint8_t, 4>{byte(s), byte(0), byte(c), 255};
            }));
        }
        addQuad(*scene, pbrMaterial(*scene, pm));
        const double theta = 80 * std::numbers::pi / 180;
        scene->lights.push_back(directional({std::sin(theta), 0, std::cos(theta)}, 1));
        scene->maxDepth = 1;
        scene->prepare();
        return estimate(*scene, towards({0, 0, 3}, {0, 0, 0}), 500).mean();
    };
    const double flat = render(false), mapped = render(true);
    const double expectedRatio =
        std::cos(35 * std::numbers::pi / 180) / std::cos(80 * std::numbers::pi / 180);
    EXPECT_NEAR(mapped / flat, expectedRatio, 0.1 * expectedRatio);
}

TEST(PbrPath, ANormalMapSeenPastItsOwnHorizonIsStillLit) {
    // The map tilts the normals 60 degrees towards +x; the camera looks from the -x side,
    // 20 degrees above the plane, so it sees the mapped normals from behind (a steep map's far
    // slopes). Lit from straight above, that side stays lit, as glTF viewers show it, and
    // no brighter than the unmapped quad (the turned normal leans away from the light).
    auto render = [](bool mapped) {
        auto scene = std::make_unique<Scene>();
        PbrMaterial pm;
        pm.baseColor = Vec3(0.8);
        pm.metallic = 0;
        pm.roughness = 1;
        pm.ior = 1;
        if (mapped) {
            const double s = std::sin(std::numbers::pi / 3), c = std::cos(std::numbers::pi / 3);
            auto byte = [](double x) { return static_cast<uint8_t>(std::lround((x + 1) * 127.5)); };
            pm.normalTexture = slot(image(1, 1, [&](int, int) {
                return std::array<uint8_t, 4>{byte(s), byte(0), byte(c), 255};
            }));
        }
        addQuad(*scene, pbrMaterial(*scene, pm));
        scene->lights.push_back(directional({0, 0, 1}, 1));
        scene->maxDepth = 1;
        scene->prepare();
        const double elevation = 20 * std::numbers::pi / 180;
        const Vec3 eye(-3 * std::cos(elevation), 0, 3 * std::sin(elevation));
        return estimate(*scene, towards(eye, {0, 0, 0}), 500).mean();
    };
    const double flat = render(false), mapped = render(true);
    EXPECT_GT(flat, 0.2);
    EXPECT_GT(mapped, 0.5 * flat);
    EXPECT_LE(mapped, flat * (1 + 1e-9));
}

TEST(PbrPath, AnAlphaMaskCutsOutTexelsForCameraRaysAndShadows) {
    auto scene = std::make_unique<Scene>();
    PbrMaterial leaf;
    leaf.baseColor = Vec3(0.1, 0.8, 0.1);
    leaf.metallic = 0;
    leaf.doubleSided = true;
    leaf.alphaMode = AlphaMode::Mask;
    leaf.alphaCutoff = 0.5;
    leaf.baseColorTexture = slot(image(
        2, 1,
        [](int x, int) {
            return std::array<uint8_t, 4>{255, 255, 255, static_cast<uint8_t>(x == 0 ? 0 : 255)};
        },
        true));
    addQuad(*scene, pbrMaterial(*scene, leaf), 1);  // the leaf at z = 1
    PbrMaterial floor;
    floor.baseColor = Vec3(0.5);
    floor.metallic = 0;
    floor.doubleSided = true;
    addQuad(*scene, pbrMaterial(*scene, floor), 0);  // the floor under it, at z = 0
    scene->lights.push_back(directional({0, 0, 1}, 1));
    scene->maxDepth = 1;
    scene->prepare();
    // Camera rays: the cut-out half shows the floor under it, lit; the opaque half the leaf.
    Hit hit;
    ASSERT_TRUE(scene->intersect(towards({-0.5, 0, 3}, {-0.5, 0, 0}), hit, true));
    EXPECT_NEAR(hit.t, 3, 1e-5);  // through the leaf to the floor
    hit = Hit{};
    ASSERT_TRUE(scene->intersect(towards({0.5, 0, 3}, {0.5, 0, 0}), hit, true));
    EXPECT_NEAR(hit.t, 2, 1e-5);
    // Shadows: under the opaque half the floor is dark; under the cut-out half it is lit.
    EXPECT_TRUE(scene->occluded(Ray{{0.5, 0, 1e-3}, {0, 0, 1}, 0, kInfinity}));
    EXPECT_FALSE(scene->occluded(Ray{{-0.5, 0, 1e-3}, {0, 0, 1}, 0, kInfinity}));
    const double lit = estimate(*scene, towards({-0.5, 0, 0.5}, {-0.5, 0.01, 0}), 200).mean();
    const double shadowed = estimate(*scene, towards({0.5, 0, 0.5}, {0.5, 0.01, 0}), 200).mean();
    EXPECT_GT(lit, 0.1);
    EXPECT_LT(shadowed, 0.2 * lit);
}

TEST(PbrPath, AnUnlitSurfaceShowsItsColourToTheCameraAndNothingElse) {
    // KHR_materials_unlit as Blender's importer maps it: camera rays see the base colour
    // (times its texture) as it is, whatever the light; other rays pass through it.
    PbrMaterial label;
    label.baseColor = Vec3(0.9, 0.5, 0.25);
    label.metallic = 0;
    label.unlit = true;
    label.baseColorTexture = slot(image(2, 1, [](int x, int) {
        return x == 0 ? std::array<uint8_t, 4>{255, 255, 255, 255}
                      : std::array<uint8_t, 4>{0, 255, 51, 255};
    }));
    auto lit = [&](bool withLabel) {  // the label at z = 1 over a floor at z = 0
        auto scene = std::make_unique<Scene>();
        if (withLabel) addQuad(*scene, pbrMaterial(*scene, label), 1);
        PbrMaterial floor;
        floor.baseColor = Vec3(0.5);
        floor.metallic = 0;
        addQuad(*scene, pbrMaterial(*scene, floor), 0);
        scene->lights.push_back(directional({0, 0, 1}, 1));
        scene->prepare();
        return scene;
    };
    auto scene = lit(true);
    // Camera rays stop at the label; shadow and other rays do not see it.
    Hit hit;
    ASSERT_TRUE(scene->intersect(towards({-0.5, 0, 3}, {-0.5, 0, 0}), hit, true));
    EXPECT_NEAR(hit.t, 2, 1e-5);
    hit = Hit{};
    ASSERT_TRUE(scene->intersect(towards({-0.5, 0, 3}, {-0.5, 0, 0}), hit, false));
    EXPECT_NEAR(hit.t, 3, 1e-5);
    EXPECT_FALSE(scene->occluded(Ray{{0.5, 0, 1e-3}, {0, 0, 1}, 0, kInfinity}));
    // Its colour, per texel (8 bits), exactly: no light added, none taken away.
    const double secondTexel[3] = {0, 1, 0.2};
    for (int c = 0; c < 3; ++c) {
        const test::MeanEstimate white =
            estimate(*scene, towards({-0.5, 0, 3}, {-0.5, 0, 1}), 16, c);
        EXPECT_NEAR(white.mean(), label.baseColor[c], 1e-6) << c;
        EXPECT_LT(white.standardError(), 1e-6) << c;  // the same every sample
        const double texel = estimate(*scene, towards({0.5, 0, 3}, {0.5, 0, 1}), 16, c).mean();
        EXPECT_NEAR(texel, label.baseColor[c] * secondTexel[c], 1e-6) << c;
    }
    // The floor under it is lit as if it were not there.
    const Ray floorRay = towards({0.5, 0, 0.5}, {0.5, 0.01, 0});
    const test::MeanEstimate under = estimate(*scene, floorRay, 400);
    const test::MeanEstimate bare = estimate(*lit(false), floorRay, 400);
    EXPECT_GT(bare.mean(), 0.1);
    EXPECT_NEAR(under.mean(), bare.mean(), kZ * (under.standardError() + bare.standardError()));
}

TEST(PbrPath, AnEmitterHiddenFromTheCameraStillLightsAndShadows) {
    // The Blender add-on's area lights, as Cycles shows them: camera rays pass through the
    // emitter; other rays see it (its light, its shadow).
    PbrMaterial lamp;
    lamp.baseColor = Vec3(0);
    lamp.metallic = 0;
    lamp.emissive = Vec3(2);
    lamp.cameraVisible = false;
    auto scene = std::make_unique<Scene>();
    const uint32_t m = pbrMaterial(*scene, lamp);
    scene->materials[m].emission = Vec3(2);
    addQuad(*scene, m, 1);
    PbrMaterial floor;
    floor.baseColor = Vec3(0.5);
    floor.metallic = 0;
    addQuad(*scene, pbrMaterial(*scene, floor), 0);
    scene->prepare();
    Hit hit;
    ASSERT_TRUE(scene->intersect(towards({0.2, 0, 3}, {0.2, 0, 0}), hit, true));
    EXPECT_NEAR(hit.t, 3, 1e-5);  // through the lamp to the floor
    hit = Hit{};
    ASSERT_TRUE(scene->intersect(towards({0.2, 0, 3}, {0.2, 0, 0}), hit, false));
    EXPECT_NEAR(hit.t, 2, 1e-5);
    EXPECT_TRUE(scene->occluded(Ray{{0.2, 0, 1e-3}, {0, 0, 1}, 0, kInfinity}));
}

TEST(PbrPath, AlphaBlendingLetsThroughTheTransparentShareOfRays) {
    auto scene = std::make_unique<Scene>();
    PbrMaterial glassy;
    glassy.doubleSided = true;
    glassy.alphaMode = AlphaMode::Blend;
    glassy.alpha = 0.3;
    addQuad(*scene, pbrMaterial(*scene, glassy));
    scene->prepare();
    int through = 0;
    const int n = 20000;
    for (int i = 0; i < n; ++i) {
        Hit hit;
        Vec3 origin(-0.5 + i * 1e-5, 0.1, 2);
        if (!scene->intersect(Ray{origin, {0, 0, -1}, 0, kInfinity}, hit, true)) ++through;
    }
    const double share = static_cast<double>(through) / n;
    EXPECT_NEAR(share, 0.7, kZ * std::sqrt(0.21 / n));
}

TEST(PbrPath, StackedAlphaBlendedLayersLetThroughTheirShareInCameraAndShadowRays) {
    // N black layers of alpha a: (1 - a)^N of what lies behind them reaches the camera, and
    // (1 - a)^N of a light above them reaches a floor below them.
    const double a = 0.3;
    for (int layers : {1, 3}) {
        const double through = std::pow(1 - a, layers);
        auto scene = std::make_unique<Scene>();
        PbrMaterial black;
        black.baseColor = Vec3(0);
        black.metallic = 1;
        black.doubleSided = true;
        black.alphaMode = AlphaMode::Blend;
        black.alpha = a;
        const uint32_t layer = pbrMaterial(*scene, black);
        for (int k = 0; k < layers; ++k) addQuad(*scene, layer, -0.5 * k);
        PbrMaterial grey;
        grey.baseColor = Vec3(0.5);
        grey.metallic = 0;
        grey.doubleSided = true;
        const uint32_t floor = pbrMaterial(*scene, grey);
        const Vec3 p[4] = {{-5, -5, -2}, {5, -5, -2}, {5, 5, -2}, {-5, 5, -2}};
        scene->primitives.addTriangle(p[0], p[1], p[2], nullptr, floor);
        scene->primitives.addTriangle(p[0], p[2], p[3], nullptr, floor);
        scene->background = Background{Vec3(1), Vec3(1)};
        scene->maxDepth = 0;
        scene->prepare();
        // Camera rays: up through the stack (from between it and the floor) to the background
        // (the layers reflect nothing at depth 0), against rays past it.
        test::MeanEstimate seen = estimate(*scene, towards({0.1, 0.2, -1.5}, {0.1, 0.2, 0}), 20000);
        EXPECT_NEAR(seen.mean(), through, kZ * seen.standardError()) << layers;
        EXPECT_EQ(estimate(*scene, towards({3, 0, 1}, {6, 0, 0}), 10).mean(), 1);

        // Shadow rays: the floor under the stack, seen from below the stack's edge and lit
        // straight from above, against the same point with nothing in the way.
        scene->background = Background{Vec3(0), Vec3(0)};
        scene->lights.push_back(directional({0, 0, 1}, 2));
        scene->maxDepth = 1;
        scene->prepare();
        const Ray atFloor = towards({3, 0.1, -1.5}, {0, 0.1, -2});
        test::MeanEstimate shaded = estimate(*scene, atFloor, 20000);
        auto open = std::make_unique<Scene>();
        const uint32_t openFloor = pbrMaterial(*open, grey);
        open->primitives.addTriangle(p[0], p[1], p[2], nullptr, openFloor);
        open->primitives.addTriangle(p[0], p[2], p[3], nullptr, openFloor);
        open->lights.push_back(directional({0, 0, 1}, 2));
        open->maxDepth = 1;
        open->prepare();
        test::MeanEstimate lit = estimate(*open, atFloor, 200);
        EXPECT_GT(lit.mean(), 0.05);
        EXPECT_NEAR(shaded.mean(), lit.mean() * through,
                    kZ * std::hypot(shaded.standardError(), lit.standardError() * through))
            << layers;
    }
}

TEST(PbrPath, AnEmissiveTextureLightsTheSceneAsMuchByLightSamplingAsByBsdfSampling) {
    auto scene = std::make_unique<Scene>();
    PbrMaterial lamp;
    lamp.doubleSided = true;
    lamp.baseColor = Vec3(0);
    lamp.emissive = Vec3(4);
    lamp.emissiveTexture = slot(image(2, 2, [](int x, int y) {
        uint8_t v = (x + y) % 2 ? 255 : 40;
        return std::array<uint8_t, 4>{v, v, v, 255};
    }));
    Material lampFlat;
    lampFlat.pbr = scene->addPbrMaterial(lamp);
    lampFlat.emission = Vec3(4) * lamp.emissiveTexture.image->average();
    const uint32_t lampId = scene->addMaterial(lampFlat);
    addQuad(*scene, lampId, 1);
    PbrMaterial floor;
    floor.baseColor = Vec3(0.7);
    floor.metallic = 0;
    floor.doubleSided = true;
    floor.roughness = 0.8;
    // The floor: a large quad 1 below the lamp.
    const Vec3 p[4] = {{-5, -5, 0}, {5, -5, 0}, {5, 5, 0}, {-5, 5, 0}};
    const uint32_t floorId = pbrMaterial(*scene, floor);
    scene->primitives.addTriangle(p[0], p[1], p[2], nullptr, floorId);
    scene->primitives.addTriangle(p[0], p[2], p[3], nullptr, floorId);
    scene->maxDepth = 1;
    scene->prepare();
    const Ray ray = towards({2, 0.5, 0.5}, {0.3, 0.2, 0});
    test::MeanEstimate lights =
        estimate(*scene, ray, 20000, 1, PathIntegrator::Strategy::LightsOnly);
    test::MeanEstimate bsdf = estimate(*scene, ray, 20000, 1, PathIntegrator::Strategy::BsdfOnly);
    test::MeanEstimate mis = estimate(*scene, ray, 20000, 1, PathIntegrator::Strategy::Mis);
    EXPECT_GT(lights.mean(), 0.05);
    EXPECT_NEAR(lights.mean(), bsdf.mean(),
                kZ * std::hypot(lights.standardError(), bsdf.standardError()));
    EXPECT_NEAR(mis.mean(), bsdf.mean(),
                kZ * std::hypot(mis.standardError(), bsdf.standardError()));
}

TEST(PbrPath, VertexColoursMultiplyTheBaseColour) {
    Primitives prims;
    const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
    TriangleExtras x;
    x.present = TriangleExtras::kColor;
    x.color = {{{1, 0, 0, 1}, {0, 1, 0, 0.5f}, {0, 0, 1, 1}}};
    const Vec3 n[3] = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
    ASSERT_TRUE(prims.addTriangle(a, b, c, n, nullptr, &x, 0));
    SurfaceInteraction si = prims.triangleAttributes(0, 0.25, 0.5);  // b0 = 0.25
    ASSERT_TRUE(si.hasColor);
    PbrMaterial pm;
    pm.baseColor = Vec3(0.5, 1, 1);
    PbrSurface s = evalSurface(pm, si);
    EXPECT_NEAR(s.baseColor.x, 0.5 * 0.25, 1e-6);
    EXPECT_NEAR(s.baseColor.y, 0.25, 1e-6);
    EXPECT_NEAR(s.baseColor.z, 0.5, 1e-6);
    EXPECT_NEAR(opacityAt(pm, si), 0.25 + 0.5 * 0.25 + 0.5, 1e-6);
}

TEST(PbrPath, AVolumeAbsorbsAlongThePathInsideIt) {
    // Light passing through a slab of thickness 1 keeps attenuationColor^(1 / distance).
    auto scene = std::make_unique<Scene>();
    PbrMaterial glass;
    glass.baseColor = Vec3(1);
    glass.metallic = 0;
    glass.roughness = 0;
    glass.transmission = 1;
    glass.ior = 1;  // nothing bends or reflects: only absorption remains
    glass.thickness = 1;
    glass.doubleSided = true;
    glass.attenuationColor = Vec3(0.5, 0.5, 0.5);
    glass.attenuationDistance = 0.5;
    const uint32_t id = pbrMaterial(*scene, glass);
    addQuad(*scene, id, 0.5);
    // The slab's far face, turned to face -z.
    const Vec3 p[4] = {{-1, -1, -0.5}, {1, -1, -0.5}, {1, 1, -0.5}, {-1, 1, -0.5}};
    scene->primitives.addTriangle(p[0], p[2], p[1], nullptr, id);
    scene->primitives.addTriangle(p[0], p[3], p[2], nullptr, id);
    scene->background = Background{Vec3(1), Vec3(1)};
    scene->maxDepth = 8;
    scene->prepare();
    // Russian roulette makes each sample 0 or 1: the mean has a standard error.
    test::MeanEstimate e = estimate(*scene, towards({0, 0, 3}, {0, 0, 0}), 4000);
    EXPECT_NEAR(e.mean(), 0.25, kZ * e.standardError());  // 0.5^(1 / 0.5)
    EXPECT_LT(e.standardError(), 0.01);
}

}  // namespace
}  // namespace glint
