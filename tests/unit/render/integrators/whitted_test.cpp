#include "glint/render/integrators/whitted.h"

#include <gtest/gtest.h>

#include <cmath>

#include "glint/scene/pbr_material.h"
#include "unit/test_support.h"

namespace glint {
namespace {

using test::expectNear;
using test::makeMaterial;

Ray makeRay(const Vec3& origin, const Vec3& dir) {
    return Ray{origin, normalize(dir), 0, kInfinity};
}

/// A large triangle in the plane z = `z` containing (0, 0, z), facing +z or -z.
void addPlane(Scene& scene, double z, const Material& m, bool facingUp = true) {
    Vec3 a{-1000, -1000, z}, b{1000, -1000, z}, c{0, 1000, z};
    uint32_t id = scene.addMaterial(m);
    if (facingUp)
        scene.primitives.addTriangle(a, b, c, nullptr, id);
    else
        scene.primitives.addTriangle(a, c, b, nullptr, id);
}

/// A small blocker: a triangle in the plane z = `z` around the z axis.
void addBlocker(Scene& scene, double z) {
    uint32_t id = scene.addMaterial(makeMaterial({1, 1, 1}));
    scene.primitives.addTriangle({-0.5, -0.5, z}, {0.5, -0.5, z}, {0, 0.5, z}, nullptr, id);
}

LightSpec pointLight(const Vec3& position, const Vec3& color, const Vec3& attenuation = {1, 0, 0}) {
    LightSpec l;
    l.kind = LightSpec::Kind::Point;
    l.position = position;
    l.color = color;
    l.attenuation = attenuation;
    return l;
}

LightSpec directionalLight(const Vec3& towards, const Vec3& color) {
    LightSpec l;
    l.kind = LightSpec::Kind::Directional;
    l.direction = normalize(towards);
    l.color = color;
    return l;
}

Vec3 shade(Scene& scene, const Ray& ray, RayCounts* out = nullptr) {
    scene.prepare();
    RayCounts counts;
    Vec3 c = WhittedIntegrator(scene).radiance(ray, 0, counts);
    if (out) *out = counts;
    return c;
}

// Most cases look at the origin of the floor z = 0 (normal +z) from straight above, or from
// (0, -3, 4): V = (0, 0.6, 0.8).
const Ray kFromAbove = makeRay({0, 0, 5}, {0, 0, -1});
const Ray kOblique = makeRay({0, -3, 4}, {0, 3, -4});

TEST(Whitted, AmbientAndEmissionAddWithoutLights) {
    Scene scene;
    Material m = makeMaterial({0.1, 0.2, 0.3}, {0.9, 0.9, 0.9});
    m.emission = {0.05, 0, 0.4};
    addPlane(scene, 0, m);
    RayCounts counts;
    expectNear(shade(scene, kFromAbove, &counts), {0.15, 0.2, 0.7});
    EXPECT_EQ(counts.camera, 1u);
    EXPECT_EQ(counts.shadow, 0u);
    EXPECT_EQ(counts.reflection, 0u);
}

TEST(Whitted, DiffuseIsScaledByNDotL) {
    Scene scene;
    addPlane(scene, 0, makeMaterial({0.1, 0.1, 0.1}, {0.5, 0.25, 1}));
    scene.lights.push_back(directionalLight({0, 1, 1}, {1, 0.5, 0.25}));  // N.L = 1/sqrt(2)
    double nl = 1 / std::sqrt(2.0);
    Vec3 expected = Vec3{0.1, 0.1, 0.1} + Vec3{0.5 * 1, 0.25 * 0.5, 1 * 0.25} * nl;
    expectNear(shade(scene, kFromAbove), expected);
    // Diffuse does not depend on the viewer.
    expectNear(shade(scene, kOblique), expected);
}

TEST(Whitted, SpecularIsBlinnPhongWithTheHalfVector) {
    Scene scene;
    addPlane(scene, 0, makeMaterial({0, 0, 0}, {0, 0, 0}, {0.5, 0.5, 0.5}, 10));
    scene.maxDepth = 0;
    scene.lights.push_back(pointLight({3, 0, 4}, {1, 1, 1}));  // L = (0.6, 0, 0.8), d = 5
    // From above: V = (0,0,1), H = (0.6, 0, 1.8) / sqrt(3.6), (N.H)^2 = 3.24 / 3.6 = 0.9.
    expectNear(shade(scene, kFromAbove), Vec3(0.5 * std::pow(0.9, 5)));
    // Obliquely: H = (0.6, 0.6, 1.6) / sqrt(3.28); exponent 10 on N.H = 1.6 / sqrt(3.28).
    expectNear(shade(scene, kOblique), Vec3(0.5 * std::pow(2.56 / 3.28, 5)));
    // Mirror configuration: V = (-0.6, 0, 0.8), H = N, the full specular colour.
    expectNear(shade(scene, makeRay({-3, 0, 4}, {3, 0, -4})), Vec3(0.5));
}

TEST(Whitted, DiffuseAndSpecularAdd) {
    Scene scene;
    addPlane(scene, 0, makeMaterial({0.1, 0.2, 0.3}, {0.4, 0.2, 0.1}, {0.25, 0.5, 1}, 10));
    scene.maxDepth = 0;
    scene.lights.push_back(pointLight({3, 0, 4}, {1, 0.5, 2}));
    Vec3 light{1, 0.5, 2};
    Vec3 expected = Vec3{0.1, 0.2, 0.3} +
                    light * (Vec3{0.4, 0.2, 0.1} * 0.8 + Vec3{0.25, 0.5, 1} * std::pow(0.9, 5));
    expectNear(shade(scene, kFromAbove), expected);
}

TEST(Whitted, PointLightsAreAttenuatedByDistance) {
    Scene scene;
    addPlane(scene, 0, makeMaterial({0, 0, 0}, {1, 1, 1}));
    // d = 2: 1 + 0.5 * 2 + 0.25 * 4 = 3.
    scene.lights.push_back(pointLight({0, 0, 2}, {0.9, 0.6, 0.3}, {1, 0.5, 0.25}));
    expectNear(shade(scene, kFromAbove), {0.3, 0.2, 0.1});
}

TEST(Whitted, DirectionalLightsAreNeverAttenuated) {
    Scene scene;
    addPlane(scene, 0, makeMaterial({0, 0, 0}, {1, 1, 1}));
    LightSpec l = directionalLight({0, 0, 1}, {0.9, 0.6, 0.3});
    l.attenuation = {1, 0.5, 0.25};
    scene.lights.push_back(l);
    expectNear(shade(scene, kFromAbove), {0.9, 0.6, 0.3});
}

TEST(Whitted, LightBehindTheSurfaceContributesNothingNotEvenSpecular) {
    Scene scene;
    addPlane(scene, 0, makeMaterial({0.1, 0.1, 0.1}, {1, 1, 1}, {1, 1, 1}, 1));
    scene.maxDepth = 0;
    // Below the floor and to the side: N.L < 0, but N.H > 0 for a viewer above.
    scene.lights.push_back(pointLight({3, 0, -1}, {1, 1, 1}));
    scene.lights.push_back(directionalLight({0, 1, -0.2}, {1, 1, 1}));
    expectNear(shade(scene, kFromAbove), {0.1, 0.1, 0.1});
    expectNear(shade(scene, kOblique), {0.1, 0.1, 0.1});
}

TEST(Whitted, BlockerBetweenPointAndLightCastsAShadow) {
    Scene scene;
    Material floor = makeMaterial({0.1, 0.2, 0.3}, {1, 1, 1});
    floor.emission = {0.01, 0.02, 0.03};
    addPlane(scene, 0, floor);
    addBlocker(scene, 2);  // between the origin and the light; the view ray passes beside it
    scene.lights.push_back(pointLight({0, 0, 4}, {1, 1, 1}));
    scene.lights.push_back(directionalLight({0, 0, 1}, {1, 1, 1}));
    RayCounts counts;
    // Ambient and emission are not shadowed.
    expectNear(shade(scene, makeRay({3, 0, 4}, {-3, 0, -4}), &counts), {0.11, 0.22, 0.33});
    EXPECT_EQ(counts.shadow, 2u);
}

TEST(Whitted, BlockerBeyondThePointLightCastsNoShadow) {
    Scene scene;
    addPlane(scene, 0, makeMaterial({0.1, 0.2, 0.3}, {0.5, 0.5, 0.5}));
    addBlocker(scene, 6);  // above the light at height 4
    scene.lights.push_back(pointLight({0, 0, 4}, {1, 1, 1}));
    expectNear(shade(scene, makeRay({3, 0, 4}, {-3, 0, -4})), {0.6, 0.7, 0.8});
    // A directional light is blocked by it: it is infinitely far away.
    scene.lights.push_back(directionalLight({0, 0, 1}, {1, 1, 1}));
    expectNear(shade(scene, makeRay({3, 0, 4}, {-3, 0, -4})), {0.6, 0.7, 0.8});
}

TEST(Whitted, MirrorReflectionIsWeightedBySpecular) {
    Scene scene;
    addPlane(scene, 0, makeMaterial({0.1, 0.1, 0.1}, {}, {0.5, 0.25, 1}));
    addPlane(scene, 10, makeMaterial({0.2, 0.4, 0.8}), false);  // a coloured ceiling, no mirror
    RayCounts counts;
    expectNear(shade(scene, kOblique, &counts), Vec3{0.1 + 0.5 * 0.2, 0.1 + 0.25 * 0.4, 0.9});
    EXPECT_EQ(counts.camera, 1u);
    EXPECT_EQ(counts.reflection, 1u);
}

TEST(Whitted, MaxDepthZeroTracesNoReflection) {
    Scene scene;
    addPlane(scene, 0, makeMaterial({0.1, 0.1, 0.1}, {}, {0.5, 0.5, 0.5}));
    addPlane(scene, 10, makeMaterial({0.2, 0.4, 0.8}), false);
    scene.maxDepth = 0;
    RayCounts counts;
    expectNear(shade(scene, kOblique, &counts), {0.1, 0.1, 0.1});
    EXPECT_EQ(counts.reflection, 0u);
}

TEST(Whitted, ReflectionsBetweenParallelMirrorsStopAtMaxDepth) {
    // Floor and ceiling both mirrors with weight 0.5: the ray alternates floor, ceiling, ...
    const Vec3 af{0.1, 0.2, 0.3}, ac{0.4, 0.2, 0.1};
    for (int maxDepth : {1, 2, 3, 5}) {
        SCOPED_TRACE(maxDepth);
        Scene scene;
        scene.maxDepth = maxDepth;
        addPlane(scene, 0, makeMaterial(af, {}, {0.5, 0.5, 0.5}));
        addPlane(scene, 10, makeMaterial(ac, {}, {0.5, 0.5, 0.5}), false);
        Vec3 expected{};
        double weight = 1;
        for (int depth = 0; depth <= maxDepth; ++depth, weight *= 0.5)
            expected += (depth % 2 == 0 ? af : ac) * weight;
        RayCounts counts;
        expectNear(shade(scene, kOblique, &counts), expected);
        EXPECT_EQ(counts.reflection, static_cast<uint64_t>(maxDepth));
    }
}

TEST(Whitted, MissesReturnAConstantBackground) {
    Scene scene;
    scene.background = {{0.3, 0.2, 0.1}, {0.3, 0.2, 0.1}};
    RayCounts counts;
    for (Vec3 d : {Vec3{0, 0, 1}, Vec3{1, -2, 3}, Vec3{0, 1, 0}})
        expectNear(shade(scene, makeRay({0, 0, 0}, d), &counts), {0.3, 0.2, 0.1});
    EXPECT_EQ(counts.shadow + counts.reflection, 0u);
}

TEST(Whitted, MissesIntoAGradientBlendDownToUp) {
    Scene scene;
    scene.background = {{1, 0, 0.5}, {0, 1, 0.25}};
    addPlane(scene, -5, makeMaterial({0.5, 0.5, 0.5}));  // geometry elsewhere does not matter
    expectNear(shade(scene, makeRay({0, 0, 0}, {0, -1, 0})), {1, 0, 0.5});
    expectNear(shade(scene, makeRay({0, 0, 0}, {0, 1, 0})), {0, 1, 0.25});
    expectNear(shade(scene, makeRay({0, 0, 0}, {1, 0, 0})), {0.5, 0.5, 0.375});
    expectNear(shade(scene, makeRay({0, 0, 0}, {0, 1, std::sqrt(3.0)})),  // y = 1/2
               {0.25, 0.75, 0.3125});
}

TEST(Whitted, ReflectionsThatMissSeeTheBackground) {
    Scene scene;
    scene.background = {{0, 0, 0}, {1, 1, 1}};
    addPlane(scene, 0, makeMaterial({0.1, 0.1, 0.1}, {}, {0.5, 0.5, 0.5}));
    // The reflected ray (0, 0.6, 0.8) has y = 0.6: the background there is 0.8.
    expectNear(shade(scene, kOblique), Vec3(0.1 + 0.5 * 0.8));
}

/// A material of a glTF file as the loader gives it to the Whitted integrator: its flat
/// course-style terms, and the physically based material they stand for (whose sidedness
/// counts).
Material gltfMaterial(Scene& scene, bool doubleSided, double roughness) {
    PbrMaterial pm;
    pm.baseColor = Vec3(0.6);
    pm.metallic = 0;
    pm.roughness = std::sqrt(roughness);
    pm.doubleSided = doubleSided;
    Material m = makeMaterial({0.05, 0.05, 0.05}, {0.6, 0.6, 0.6}, {0.3, 0.3, 0.3}, 10);
    m.roughness = roughness;
    m.pbr = scene.addPbrMaterial(pm);
    return m;
}

TEST(Whitted, ADoubleSidedGltfMaterialIsLitOnItsBackFaceAsOnItsFront) {
    // The floor seen and lit from above, and the same seen and lit from below: the glTF
    // specification turns a double-sided material's back-face normal towards the viewer.
    for (double roughness : {0.0, 0.3}) {
        auto render = [&](double side) {
            Scene scene;
            addPlane(scene, 0, gltfMaterial(scene, true, roughness));
            scene.maxDepth = 0;
            scene.lights.push_back(pointLight({3, 0, 4 * side}, {1, 1, 1}));
            scene.lights.push_back(directionalLight({0, 1, 2 * side}, {0.5, 0.5, 0.5}));
            return shade(scene, makeRay({0, -3, 4 * side}, {0, 3, -4 * side}));
        };
        const Vec3 front = render(1), back = render(-1);
        EXPECT_GT(front.y, 0.5) << roughness;  // lit: well above the ambient 0.05
        expectNear(back, front);
    }
}

TEST(Whitted, ASingleSidedGltfMaterialAndTheCoursesMaterialsKeepTheirBackFacesUnlit) {
    // Seen from below and lit from below: camera rays pass a single-sided back face (glTF's
    // culling) to the background; other rays see it, unlit but for its ambient term, as they
    // see the back of a course triangle.
    for (bool gltf : {true, false}) {
        Scene scene;
        scene.background = Background{Vec3(0.25), Vec3(0.25)};
        addPlane(scene, 0,
                 gltf ? gltfMaterial(scene, false, 0)
                      : makeMaterial({0.05, 0.05, 0.05}, {0.6, 0.6, 0.6}, {0.3, 0.3, 0.3}, 10));
        scene.maxDepth = 0;
        scene.lights.push_back(directionalLight({0, 1, -2}, {1, 1, 1}));
        const Ray fromBelow = makeRay({0, -3, -4}, {0, 3, 4});
        scene.prepare();
        RayCounts counts;
        const WhittedIntegrator whitted(scene);
        expectNear(whitted.radiance(fromBelow, 0, counts), gltf ? Vec3(0.25) : Vec3(0.05));
        expectNear(whitted.radiance(fromBelow, 1, counts), Vec3(0.05));  // a secondary ray
    }
}

TEST(Whitted, StackedAlphaBlendedLayersLetThroughTheirShareInCameraAndShadowRays) {
    // N layers of alpha a (black, opaque in their flat terms: the traversal blends, as the
    // loaders leave it) between the viewer and the background, and between a floor and its
    // light: (1 - a)^N of each gets through, in the mean over rays.
    const double a = 0.3;
    for (int layers : {1, 3}) {
        Scene scene;
        PbrMaterial pm;
        pm.alphaMode = AlphaMode::Blend;
        pm.alpha = a;
        pm.doubleSided = true;
        Material black = makeMaterial({0, 0, 0});
        black.pbr = scene.addPbrMaterial(pm);
        const uint32_t id = scene.addMaterial(black);
        for (int k = 0; k < layers; ++k) {
            const double z = 1 + 0.5 * k;
            scene.primitives.addTriangle({-1, -1, z}, {1, -1, z}, {0, 1, z}, nullptr, id);
        }
        addPlane(scene, 0, makeMaterial({0, 0, 0}, {0.5, 0.5, 0.5}));
        scene.background = Background{Vec3(1), Vec3(1)};
        scene.lights.push_back(directionalLight({0, 0, 1}, {1, 1, 1}));
        scene.maxDepth = 0;
        scene.prepare();
        const WhittedIntegrator whitted(scene);
        const int n = 20000;
        double up = 0, down = 0;
        for (int i = 0; i < n; ++i) {
            RayCounts counts;
            const double dx = 1e-7 * i;  // rays that differ, so that their blending does
            // Up from the floor through the stack to the background.
            up += whitted.radiance(makeRay({dx, 0, 0.5}, {0, 0, 1}), 0, counts).y;
            // Down onto the floor, from beside the stack: its shadow ray crosses the stack.
            down += whitted.radiance(makeRay({3 + dx, 0, 0.5}, {-3, 0, -0.5}), 0, counts).y;
        }
        const double through = std::pow(1 - a, layers);
        const double tolerance = 5 * std::sqrt(through * (1 - through) / n);
        EXPECT_NEAR(up / n, through, tolerance) << layers;
        EXPECT_NEAR(down / n, 0.5 * through, 0.5 * tolerance) << layers;
    }
}

}  // namespace
}  // namespace glint
