// Motion blur of animated glTF files (io/registry.cpp addMotion, geometry/deforming_mesh.h):
// one motion, a square sliding one unit along x in the shutter, given three ways (a node's
// translation, a morph target's weight, a skin's joint) blurs to the same image: the rigid
// one through a moving instance, the two deforming ones through vertices keyed over the shutter.

#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "glint/io/registry.h"
#include "glint/render/renderer.h"
#include "unit/io/gltf/gltf_asset_builder.h"
#include "unit/test_support.h"

namespace glint {
namespace {

using namespace glint::test;

/// A glowing unit square facing +z, moved one unit along x over the first second by `how`:
/// "translation", "weights" (a morph target displacing every vertex by (1, 0, 0)) or "skin" (a
/// joint that every vertex follows).
std::string slidingSquare(const std::string& how) {
    GltfAsset a;
    const int position = a.floats({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0}, "VEC3");
    const int normal = a.floats({0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3");
    const int indices = a.integers({0, 1, 2, 0, 2, 3}, GltfAsset::kUshort, "SCALAR");
    const int shift = a.floats({1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0}, "VEC3");
    const int joints = a.integers(std::vector<int>(16, 0), GltfAsset::kUbyte, "VEC4");
    const int weights = a.floats({1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0}, "VEC4");
    const int times = a.floats({0, 1}, "SCALAR");
    const int moves =
        how == "weights" ? a.floats({0, 1}, "SCALAR") : a.floats({0, 0, 0, 1, 0, 0}, "VEC3");
    std::string attributes =
        R"("POSITION": )" + std::to_string(position) + R"(, "NORMAL": )" + std::to_string(normal);
    if (how == "skin")
        attributes += R"(, "JOINTS_0": )" + std::to_string(joints) + R"(, "WEIGHTS_0": )" +
                      std::to_string(weights);
    std::string primitive = R"({"attributes": {)" + attributes +
                            R"(}, "material": 0, "indices": )" + std::to_string(indices);
    if (how == "weights")
        primitive += R"(, "targets": [{"POSITION": )" + std::to_string(shift) + "}]";
    primitive += "}";
    const std::string nodes = how == "skin"
                                  ? R"([{"mesh": 0, "skin": 0}, {}], "skins": [{"joints": [1]}],
                         "scenes": [{"nodes": [0, 1]}])"
                                  : R"([{"mesh": 0}])";
    const int target = how == "skin" ? 1 : 0;
    // Glowing white, to stand out of the grey floor behind it.
    return a.text(
        R"("materials": [{"emissiveFactor": [1, 1, 1], "pbrMetallicRoughness":
                      {"baseColorFactor": [0, 0, 0, 1]}}], "meshes": [{"primitives": [)" +
        primitive + R"(]}], "nodes": )" + nodes + R"(, "animations": [{"samplers": [{"input": )" +
        std::to_string(times) + R"(, "output": )" + std::to_string(moves) +
        R"(}], "channels": [{"sampler": 0, "target": {"node": )" + std::to_string(target) +
        R"(, "path": ")" + (how == "skin" ? std::string("translation") : how) + R"("}}]}])");
}

class GltfMotionBlur : public TempDirTest {
  protected:
    /// `how`'s square rendered at 48 x 32 in the classic look (Whitted) at `seconds`, with the
    /// shutter open from `open` to `close` seconds after it.
    Film render(const std::string& how, double seconds, double open = 0, double close = 0) {
        const std::string file = path(how + ".gltf");
        std::ofstream(file) << slidingSquare(how);
        LoadOptions options;
        options.width = 48;
        options.height = 32;
        options.look = ModelLook::classic();
        options.time.seconds = seconds;
        options.time.shutterOpen = open;
        options.time.shutterClose = close;
        std::vector<Diagnostic> warnings;
        ModelScene m = loadSceneFile(file, warnings, options);
        for (const Diagnostic& w : warnings) ADD_FAILURE() << w.format("warning");
        m.scene->prepare();
        // Moved rigidly, the square is an instance of a still mesh; deformed, of a deforming one.
        const Primitives& prims = m.scene->primitives;
        EXPECT_EQ(prims.sharedMeshCount(), close > open ? 1u : 0u);
        for (uint32_t i = 0; i < prims.sharedMeshCount(); ++i)
            EXPECT_EQ(prims.sharedMesh(i).deformation() != nullptr, how != "translation");
        RenderOptions o;
        o.threads = 2;
        o.spp = 64;
        o.seed = 3;
        return glint::render(*m.scene, o).film;
    }
};

/// The mean over pixels of the largest difference of a channel.
double meanDifference(const Film& a, const Film& b) {
    double sum = 0;
    for (int y = 0; y < a.height(); ++y)
        for (int x = 0; x < a.width(); ++x) {
            const Vec3 d = a.at(x, y) - b.at(x, y);
            sum += std::max({std::abs(d.x), std::abs(d.y), std::abs(d.z)});
        }
    return sum / (a.width() * a.height());
}

TEST_F(GltfMotionBlur, ASlidingSquareBlursAlikeMovedByItsNodeItsMorphTargetOrItsSkin) {
    const Film rigid = render("translation", 0, 0, 1);
    const Film morphed = render("weights", 0, 0, 1);
    const Film skinned = render("skin", 0, 0, 1);
    ASSERT_EQ(rigid.width(), 48);
    // The same rays at the same times meet the same square: only rounding tells them apart.
    EXPECT_LT(meanDifference(rigid, morphed), 1e-3);
    EXPECT_LT(meanDifference(rigid, skinned), 1e-3);
    // And the blur is there: the still square at the shutter's middle is far from it.
    const Film still = render("weights", 0.5);
    EXPECT_GT(meanDifference(still, morphed), 0.02);
    EXPECT_LT(meanDifference(still, render("translation", 0.5)), 1e-3);
}

}  // namespace
}  // namespace glint
