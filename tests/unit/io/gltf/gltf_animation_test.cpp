// glTF animations played (io/gltf/gltf_animations.cpp): an animated file posed at a time gives
// the model a static file gives whose nodes hold the values interpolated by hand, for node
// transforms, morph weights, skins' joints and cameras; bad animation data is refused with the
// animation and sampler named; a file is parsed once and posed at many times.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "glint/io/gltf/gltf_loader.h"
#include "glint/io/registry.h"
#include "unit/io/gltf/gltf_asset_builder.h"
#include "unit/io/gltf/gltf_test_support.h"
#include "unit/test_support.h"

namespace glint {
namespace {

using namespace glint::test;
using ::testing::HasSubstr;

/// An asset of one mesh (a triangle (0,0,0) (1,0,0) (0,1,0), with a morph target that moves
/// its third vertex by (0, 0, 2)), the nodes `nodes` (a JSON array) and, when given, the
/// animations `animations` (a JSON array). Accessors for key times and values are added with
/// `asset` before text() is called.
struct Animated {
    GltfAsset asset;
    int position, target;

    Animated() {
        position = asset.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
        target = asset.floats({0, 0, 0, 0, 0, 0, 0, 0, 2}, "VEC3");
    }
    std::string text(const std::string& nodes, const std::string& animations = "",
                     const std::string& more = "") const {
        return asset.text(R"("meshes": [{"primitives": [{"attributes": {"POSITION": )" +
                          std::to_string(position) + R"(}, "targets": [{"POSITION": )" +
                          std::to_string(target) + R"(}]}]}], "nodes": )" + nodes +
                          (animations.empty() ? "" : R"(, "animations": )" + animations) + more);
    }
};

/// `text` parsed and posed at `seconds` of its first animation (none: not played).
Model posed(const std::string& text, std::optional<double> seconds,
            const std::string& animation = "") {
    std::vector<Diagnostic> warnings;
    GltfOptions options;
    options.time.animation = animation;
    options.time.seconds = seconds;
    Model m = parseGltf(text, "anim.gltf", warnings, options);
    for (const Diagnostic& w : warnings) ADD_FAILURE() << w.format("warning");
    return m;
}

/// Every placed vertex of `m`, placement by placement.
std::vector<Vec3> placedVertices(const Model& m) {
    std::vector<Vec3> out;
    for (const ModelPlacement& p : m.placements)
        for (const Vec3f& v : m.meshes[p.mesh].positions)
            out.push_back(p.worldFromObject.point(Vec3(v)));
    return out;
}

void expectSameVertices(const Model& a, const Model& b, double tolerance = 1e-6) {
    std::vector<Vec3> va = placedVertices(a), vb = placedVertices(b);
    ASSERT_EQ(va.size(), vb.size());
    ASSERT_FALSE(va.empty());
    for (size_t i = 0; i < va.size(); ++i) {
        EXPECT_NEAR(va[i].x, vb[i].x, tolerance) << "vertex " << i;
        EXPECT_NEAR(va[i].y, vb[i].y, tolerance) << "vertex " << i;
        EXPECT_NEAR(va[i].z, vb[i].z, tolerance) << "vertex " << i;
    }
}

/// A channel and a sampler, as JSON: `node`.`path` from accessors `input` and `output`.
std::string channel(int sampler, int node, const char* path) {
    return R"({"sampler": )" + std::to_string(sampler) + R"(, "target": {"node": )" +
           std::to_string(node) + R"(, "path": ")" + path + "\"}}";
}
std::string sampler(int input, int output, const char* interpolation = "LINEAR") {
    return R"({"input": )" + std::to_string(input) + R"(, "output": )" + std::to_string(output) +
           R"(, "interpolation": ")" + interpolation + "\"}";
}

TEST(GltfAnimation, NodesTakeTheInterpolatedTranslationRotationAndScale) {
    Animated a;
    int times = a.asset.floats({0, 2}, "SCALAR");
    int moves = a.asset.floats({0, 0, 0, 2, 4, 0}, "VEC3");
    const double s = std::sin(std::numbers::pi / 4), c = std::cos(std::numbers::pi / 4);
    // A quarter turn about z over two seconds.
    int turns = a.asset.floats({0, 0, 0, 1, 0, 0, float(s), float(c)}, "VEC4");
    int stepTimes = a.asset.floats({0, 1}, "SCALAR");
    int scales = a.asset.floats({1, 1, 1, 2, 2, 2}, "VEC3");
    const std::string animated =
        a.text(R"([{"mesh": 0, "children": [1]}, {"mesh": 0, "translation": [0, 0, 5]}])",
               R"([{"name": "Move", "samplers": [)" + sampler(times, moves) + ", " +
                   sampler(times, turns) + ", " + sampler(stepTimes, scales, "STEP") +
                   R"(], "channels": [)" + channel(0, 0, "translation") + ", " +
                   channel(1, 0, "rotation") + ", " + channel(2, 0, "scale") + "]}]");
    // By hand: at 0.5 s a quarter of the way (an eighth of a turn of 90 degrees: 22.5), the
    // scale still the first key's; at 1.5 s three quarters, and the second scale.
    auto still = [&](double x, double y, double degrees, double scale) {
        const double half = degrees * std::numbers::pi / 360;
        char node[1024];
        std::snprintf(node, sizeof node,
                      R"([{"mesh": 0, "children": [1], "translation": [%.17g, %.17g, 0],
                          "rotation": [0, 0, %.17g, %.17g], "scale": [%g, %g, %g]},
                         {"mesh": 0, "translation": [0, 0, 5]}])",
                      x, y, std::sin(half), std::cos(half), scale, scale, scale);
        return a.text(node);
    };
    expectSameVertices(posed(animated, 0.5), posed(still(0.5, 1, 22.5, 1), std::nullopt));
    expectSameVertices(posed(animated, 1.5), posed(still(1.5, 3, 67.5, 2), std::nullopt));
    // Outside the keys, the first and the last.
    expectSameVertices(posed(animated, -3), posed(still(0, 0, 0, 1), std::nullopt));
    expectSameVertices(posed(animated, 9), posed(still(2, 4, 90, 2), std::nullopt));
    Model m = posed(animated, 1.5);
    EXPECT_EQ(m.posed, "animation 0 'Move' at 1.5 s");
    ASSERT_EQ(m.animations.size(), 1u);
    EXPECT_EQ(m.animations[0].name, "Move");
    EXPECT_EQ(m.animations[0].start, 0);
    EXPECT_EQ(m.animations[0].end, 2);
    EXPECT_EQ(m.animations[0].channels, 3u);
}

TEST(GltfAnimation, ACubicSplineFollowsItsTangents) {
    Animated a;
    int times = a.asset.floats({1, 3}, "SCALAR");
    // In-tangent, value, out-tangent per key: from (0,0,0) leaving at (1,0,0) per second, to
    // (4,0,0) arriving at (0,2,0) per second.
    int values = a.asset.floats({9, 9, 9, 0, 0, 0, 1, 0, 0, 0, 2, 0, 4, 0, 0, 9, 9, 9}, "VEC3");
    const std::string animated = a.text(
        R"([{"mesh": 0}])", R"([{"samplers": [)" + sampler(times, values, "CUBICSPLINE") +
                                R"(], "channels": [)" + channel(0, 0, "translation") + "]}]");
    // At 2 s: s = 0.5, d = 2. v = 0.5 v0 + d (0.125) b0 + 0.5 v1 + d (-0.125) a1
    //   = (0, 0, 0) + (0.25, 0, 0) + (2, 0, 0) - (0, 0.5, 0) = (2.25, -0.5, 0).
    expectSameVertices(
        posed(animated, 2),
        posed(a.text(R"([{"mesh": 0, "translation": [2.25, -0.5, 0]}])"), std::nullopt));
}

TEST(GltfAnimation, MorphWeightsAreAnimated) {
    Animated a;
    int times = a.asset.floats({0, 1}, "SCALAR");
    int weights = a.asset.floats({0, 1}, "SCALAR");
    const std::string animated =
        a.text(R"([{"mesh": 0, "weights": [0.9]}])",
               R"([{"samplers": [)" + sampler(times, weights) + R"(], "channels": [)" +
                   channel(0, 0, "weights") + "]}]");
    expectSameVertices(posed(animated, 0.25),
                       posed(a.text(R"([{"mesh": 0, "weights": [0.25]}])"), std::nullopt));
    // Not played: the node's own weights.
    Model still = posed(animated, std::nullopt);
    EXPECT_NEAR(placedVertices(still)[2].z, 1.8, 1e-6);
    EXPECT_TRUE(still.posed.empty());
}

TEST(GltfAnimation, NormalisedIntegerRotationsAreRead) {
    Animated a;
    int times = a.asset.floats({0, 1}, "SCALAR");
    // Identity, then a half turn about z, as normalised shorts (32767 is 1).
    int turns = a.asset.integers({0, 0, 0, 32767, 0, 0, 32767, 0}, GltfAsset::kShort, "VEC4", true);
    const std::string animated =
        a.text(R"([{"mesh": 0}])", R"([{"samplers": [)" + sampler(times, turns) +
                                       R"(], "channels": [)" + channel(0, 0, "rotation") + "]}]");
    const double h = std::sqrt(0.5);
    char still[512];
    std::snprintf(still, sizeof still, R"([{"mesh": 0, "rotation": [0, 0, %.17g, %.17g]}])", h, h);
    expectSameVertices(posed(animated, 0.5), posed(a.text(still), std::nullopt), 1e-4);
}

TEST(GltfAnimation, SkinsFollowTheirAnimatedJoints) {
    Animated a;
    int joints = a.asset.integers({0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0}, GltfAsset::kUbyte, "VEC4");
    int weights = a.asset.floats({1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0}, "VEC4");
    int times = a.asset.floats({0, 1}, "SCALAR");
    int moves = a.asset.floats({0, 1, 0, 3, 1, 0}, "VEC3");
    // Node 0 places the skinned mesh; 1 is the root joint, 2 its child that moves.
    auto text = [&](const std::string& childTranslation, const std::string& animations) {
        return a.asset.text(R"("meshes": [{"primitives": [{"attributes": {"POSITION": )" +
                            std::to_string(a.position) + R"(, "JOINTS_0": )" +
                            std::to_string(joints) + R"(, "WEIGHTS_0": )" +
                            std::to_string(weights) +
                            R"(}}]}], "skins": [{"joints": [1, 2]}],
               "nodes": [{"mesh": 0, "skin": 0}, {"children": [2]},
                         {"translation": )" +
                            childTranslation + R"(}], "scenes": [{"nodes": [0, 1]}])" +
                            (animations.empty() ? "" : R"(, "animations": )" + animations));
    };
    const std::string animated =
        text("[0, 1, 0]", R"([{"samplers": [)" + sampler(times, moves) + R"(], "channels": [)" +
                              channel(0, 2, "translation") + "]}]");
    const Model m = posed(animated, 0.5);
    expectSameVertices(m, posed(text("[1.5, 1, 0]", ""), std::nullopt));
    // The vertex on the moving joint moved; the others did not.
    std::vector<Vec3> v = placedVertices(m);
    EXPECT_NEAR(v[0].x, 0, 1e-6);
    EXPECT_NEAR(v[2].x, 1.5, 1e-6);
    EXPECT_NEAR(v[2].y, 2, 1e-6);
}

TEST(GltfAnimation, CamerasAndLightsFollowTheirAnimatedNodes) {
    Animated a;
    int times = a.asset.floats({0, 4}, "SCALAR");
    int moves = a.asset.floats({0, 0, 10, 8, 0, 10}, "VEC3");
    const std::string more =
        R"(, "cameras": [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1}}],
            "extensions": {"KHR_lights_punctual": {"lights": [{"type": "point", "intensity": 5}]}},
            "extensionsUsed": ["KHR_lights_punctual"])";
    const std::string animated = a.text(
        R"([{"mesh": 0}, {"camera": 0, "translation": [0, 0, 10]},
            {"translation": [0, 0, 10], "extensions": {"KHR_lights_punctual": {"light": 0}}}])",
        R"([{"samplers": [)" + sampler(times, moves) + R"(], "channels": [)" +
            channel(0, 1, "translation") + ", " + channel(0, 2, "translation") + "]}]",
        more);
    Model m = posed(animated, 1);
    ASSERT_TRUE(m.camera);
    EXPECT_NEAR(m.camera->spec.eye.x, 2, 1e-9);
    EXPECT_NEAR(m.camera->spec.eye.z, 10, 1e-9);
    ASSERT_EQ(m.lights.size(), 1u);
    EXPECT_NEAR(m.lights[0].position.x, 2, 1e-9);
}

TEST(GltfAnimation, AnAnimationIsChosenByIndexOrName) {
    Animated a;
    int times = a.asset.floats({0, 1}, "SCALAR");
    int up = a.asset.floats({0, 0, 0, 0, 1, 0}, "VEC3");
    int side = a.asset.floats({0, 0, 0, 1, 0, 0}, "VEC3");
    const std::string animated = a.text(
        R"([{"mesh": 0}])", R"([{"name": "Up", "samplers": [)" + sampler(times, up) +
                                R"(], "channels": [)" + channel(0, 0, "translation") +
                                R"(]}, {"name": "Side", "samplers": [)" + sampler(times, side) +
                                R"(], "channels": [)" + channel(0, 0, "translation") + "]}]");
    EXPECT_NEAR(placedVertices(posed(animated, 1))[0].y, 1, 1e-9);
    EXPECT_NEAR(placedVertices(posed(animated, 1, "1"))[0].x, 1, 1e-9);
    EXPECT_NEAR(placedVertices(posed(animated, 1, "Side"))[0].x, 1, 1e-9);
    GltfOptions options;
    options.time = {"Walk", 1.0};
    EXPECT_THAT(errorParsing(animated, options).message,
                HasSubstr("no animation is named 'Walk': the file has 2 animations: 0 = 'Up' "
                          "(0 to 1 s), 1 = 'Side' (0 to 1 s)"));
    options.time = {"2", 1.0};
    EXPECT_THAT(errorParsing(animated, options).message, HasSubstr("there is no animation 2"));
    // A file without animations stays still at any time, unless one is named.
    Model still = posed(a.text(R"([{"mesh": 0}])"), 3);
    EXPECT_TRUE(still.posed.empty());
    options.time = {"0", 1.0};
    EXPECT_THAT(errorParsing(a.text(R"([{"mesh": 0}])"), options).message,
                HasSubstr("the file has no animations"));
}

/// The message of parsing `text` posed at 0.5 s.
std::string playError(const std::string& text) {
    GltfOptions options;
    options.time.seconds = 0.5;
    return errorParsing(text, options).message;
}

TEST(GltfAnimation, BadAnimationDataIsRefusedNamingTheAnimationAndSampler) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    auto bad = [&](std::initializer_list<float> times, std::initializer_list<float> values,
                   const char* type, const char* path, const char* interpolation = "LINEAR",
                   const std::string& nodes = R"([{"mesh": 0}])") {
        Animated a;
        int in = a.asset.floats(times, "SCALAR");
        int out = a.asset.floats(values, type);
        return playError(a.text(nodes, R"([{"name": "Bad", "samplers": [{"input": 99, "output": 0},
                                            )" +
                                           sampler(in, out, interpolation) + R"(], "channels": [)" +
                                           channel(1, 0, path) + "]}]"));
    };
    EXPECT_THAT(bad({0, 1, 1}, {0, 0, 0, 1, 1, 1, 2, 2, 2}, "VEC3", "translation"),
                HasSubstr("animation 0 'Bad', sampler 1 (translation of node 0): key times must "
                          "increase, but time 2 (1.000000) is not after time 1"));
    EXPECT_THAT(bad({0, 1}, {0, 0, 0, 1, 1, 1, 2, 2, 2}, "VEC3", "translation"),
                HasSubstr("animation 0 'Bad', sampler 1: it has 2 key times and 3 output values, "
                          "not 2"));
    EXPECT_THAT(bad({0, nan}, {0, 0, 0, 1, 1, 1}, "VEC3", "translation"),
                HasSubstr("(input of animation 0 'Bad', sampler 1): element 1 is not finite"));
    EXPECT_THAT(bad({0, 1}, {0, 0, 0, 1, nan, 1}, "VEC3", "scale"),
                HasSubstr("(output of animation 0 'Bad', sampler 1): element 1 is not finite"));
    EXPECT_THAT(bad({0, 1}, {0, 0, 0, 1, 1, 1}, "VEC3", "rotation"),
                HasSubstr("a rotation needs 4 components per element, it has 3"));
    EXPECT_THAT(bad({0, 1}, {0, 0, 0, 0, 0, 0, 0, 1}, "VEC4", "rotation"),
                HasSubstr("animation 0 'Bad', sampler 1 (rotation of node 0)"));
    EXPECT_THAT(bad({0, 1}, {0, 1, 2}, "SCALAR", "weights"),
                HasSubstr("animation 0 'Bad', sampler 1: it has 2 key times and 3 output values, "
                          "not 2 (1 morph weights per key)"));
    EXPECT_THAT(bad({0, 1}, {0, 0, 0, 1, 1, 1}, "VEC3", "translation", "BOUNCY"),
                HasSubstr("animation 0 'Bad', sampler 1: interpolation 'BOUNCY' is not LINEAR, "
                          "STEP or CUBICSPLINE"));
    EXPECT_THAT(bad({0, 1}, {0, 0, 0, 1, 1, 1}, "VEC3", "translation", "LINEAR",
                    R"([{"mesh": 0, "matrix": [1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1]}])"),
                HasSubstr("animation 0 'Bad', channel 0: it animates node 0, which has a matrix"));
    Animated a;
    int in = a.asset.floats({0, 1}, "SCALAR");
    EXPECT_THAT(playError(a.text(R"([{"mesh": 0}])", R"([{"samplers": [)" + sampler(in, in) +
                                                         R"(], "channels": [)" +
                                                         channel(0, 7, "scale") + "]}]")),
                HasSubstr("node 7 does not exist (the file has 1 node): animation 0, channel 0 "
                          "refers to it"));
}

TEST(GltfAnimation, ABrokenAnimationNotPlayedLeavesTheStillModel) {
    Animated a;
    int in = a.asset.floats({1, 0}, "SCALAR");
    const std::string text = a.text(R"([{"mesh": 0, "translation": [1, 2, 3]}])",
                                    R"([{"samplers": [)" + sampler(in, in) + R"(], "channels": [)" +
                                        channel(0, 0, "scale") + "]}]");
    Model m = posed(text, std::nullopt);
    EXPECT_NEAR(placedVertices(m)[0].y, 2, 1e-9);
    ASSERT_EQ(m.animations.size(), 1u);
    EXPECT_EQ(m.animations[0].end, 1);  // read from the times: the accessor has no min or max
}

TEST(GltfAnimation, AFileParsedOncePosesAtEveryTimeAsAFreshParse) {
    Animated a;
    int times = a.asset.floats({0, 1, 2}, "SCALAR");
    int moves = a.asset.floats({0, 0, 0, 1, 3, 0, 2, 0, 1}, "VEC3");
    const std::string text = a.text(
        R"([{"mesh": 0}])", R"([{"samplers": [)" + sampler(times, moves) + R"(], "channels": [)" +
                                channel(0, 0, "translation") + "]}]");
    std::vector<Diagnostic> warnings;
    GltfDocument document(text, "anim.gltf", warnings);
    for (double t : {1.5, 0.25, 2.0, 0.25}) {
        ModelTime time{"", t};
        expectSameVertices(document.pose(time, warnings), posed(text, t), 0);
    }
    EXPECT_EQ(document.animations().size(), 1u);
    EXPECT_TRUE(warnings.empty());
}

// KHR_animation_pointer: channels that animate a material's factors and an extension's number,
// a light's intensity, a camera's field of view and a node's translation (JSON pointers into
// the file) set them at
// the time posed; a later pose without the animation has the file's own values back; a target
// Glint does not play is warned of once.
TEST(GltfAnimation, PointersAnimateMaterialsLightsAndCameras) {
    Animated a;
    int times = a.asset.floats({0, 2}, "SCALAR");
    int emissive = a.asset.floats({0, 0, 0, 1, 0.5f, 0}, "VEC3");
    int strength = a.asset.floats({1, 3}, "SCALAR");
    int intensity = a.asset.floats({1, 5}, "SCALAR");
    int fov = a.asset.floats({0.5f, 1.0f}, "SCALAR");
    int moves = a.asset.floats({0, 0, 0, 2, 0, 0}, "VEC3");
    auto pointer = [](int sampler, const std::string& to) {
        return R"({"sampler": )" + std::to_string(sampler) +
               R"(, "target": {"path": "pointer", "extensions": {"KHR_animation_pointer":
               {"pointer": ")" +
               to + "\"}}}}";
    };
    const std::string text = a.text(
        R"([{"mesh": 0}, {"camera": 0, "translation": [0, 0, 5]},
            {"translation": [0, 3, 0], "extensions": {"KHR_lights_punctual": {"light": 0}}}])",
        R"([{"name": "Glow", "samplers": [)" + sampler(times, emissive) + ", " +
            sampler(times, strength) + ", " + sampler(times, intensity) + ", " +
            sampler(times, fov) + ", " + sampler(times, strength) + ", " + sampler(times, moves) +
            R"(], "channels": [)" + pointer(0, "/materials/0/emissiveFactor") + ", " +
            pointer(1, "/materials/0/extensions/KHR_materials_emissive_strength/emissiveStrength") +
            ", " + pointer(2, "/extensions/KHR_lights_punctual/lights/0/intensity") + ", " +
            pointer(3, "/cameras/0/perspective/yfov") + ", " +
            pointer(4, "/materials/0/alphaMode") + ", " + pointer(5, "/nodes/0/translation") +
            "]}]",
        R"(, "materials": [{"emissiveFactor": [0, 0, 0],
              "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 1}}}],
            "cameras": [{"type": "perspective", "perspective": {"yfov": 0.5, "znear": 0.1}}],
            "extensionsUsed": ["KHR_animation_pointer", "KHR_lights_punctual",
                               "KHR_materials_emissive_strength"],
            "extensions": {"KHR_lights_punctual": {"lights": [{"type": "point",
                                                               "intensity": 1}]}})");
    // Point the triangle at material 0.
    std::string withMaterial = text;
    withMaterial.replace(withMaterial.find(R"("targets")"), 9, R"("material": 0, "targets")");
    std::vector<Diagnostic> warnings;
    GltfDocument doc(withMaterial, "pointer.gltf", warnings, {});
    auto at = [&](std::optional<double> seconds) {
        ModelTime time;
        time.seconds = seconds;
        return doc.pose(time, warnings);
    };
    Model half = at(1);  // halfway
    ASSERT_EQ(half.meshes.size(), 1u);
    const PbrMaterial& glow = *half.meshes[0].materials.at(0).pbr;
    expectNear(glow.emissive, Vec3(0.5, 0.25, 0) * 2.0, 1e-6);  // the factor times strength 2
    ASSERT_EQ(half.lights.size(), 1u);
    expectNear(half.lights[0].color, Vec3(3), 1e-6);
    // A pointer to a node's translation moves it as the node's own channel would: 1 along x.
    ASSERT_EQ(half.placements.size(), 1u);
    expectNear(half.placements[0].worldFromObject.point(Vec3(0)), Vec3(1, 0, 0), 1e-6);
    ASSERT_TRUE(half.camera);
    EXPECT_NEAR(half.camera->spec.fovyDegrees, 0.75 * 180 / std::numbers::pi, 1e-4);
    // The one target not played, said once however often it is posed.
    Model again = at(2);
    expectNear(again.lights[0].color, Vec3(5), 1e-6);
    size_t said = 0;
    for (const Diagnostic& w : warnings) said += w.message.find("alphaMode") != std::string::npos;
    EXPECT_EQ(said, 1u);
    // Not played: the file's own values.
    Model still = at(std::nullopt);
    expectNear(still.meshes[0].materials.at(0).pbr->emissive, Vec3(0), 1e-12);
    expectNear(still.lights[0].color, Vec3(1), 1e-12);
    EXPECT_NEAR(still.camera->spec.fovyDegrees, 0.5 * 180 / std::numbers::pi, 1e-9);
}

}  // namespace
}  // namespace glint
