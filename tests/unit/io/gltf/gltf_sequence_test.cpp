// Frames of a sequence (scene/scene.h FrameAccel, Bvh::refit): each frame of an animated model
// prepared by refitting the last frame's BVHs renders exactly as the frame prepared anew, still
// or blurred; a tree that grew too slow to search is built anew.

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "glint/io/registry.h"
#include "glint/render/renderer.h"
#include "unit/io/gltf/gltf_test_support.h"

namespace glint {
namespace {

using test::dataPath;

/// tests/data/gltf/animated.gltf (a box turning as it rises and falls, another stepping) posed
/// at `seconds`, with a shutter of `shutter` seconds (then the turning box is a moving
/// instance of a shared mesh).
std::unique_ptr<Scene> frameAt(double seconds, double shutter, AssetCache& assets) {
    LoadOptions options;
    options.width = 40;
    options.height = 30;
    options.look = ModelLook::classic();
    options.time.seconds = seconds;
    options.time.shutterClose = shutter;
    options.assets = &assets;
    std::vector<Diagnostic> warnings;
    return loadSceneFile(dataPath("animated.gltf"), warnings, options).scene;
}

Film renderFrame(const Scene& scene) {
    RenderOptions o;
    o.threads = 2;
    o.spp = 4;
    o.seed = 5;
    return render(scene, o).film;
}

void expectSameImage(const Film& a, const Film& b, double seconds) {
    ASSERT_EQ(a.width(), b.width());
    for (int y = 0; y < a.height(); ++y)
        for (int x = 0; x < a.width(); ++x)
            ASSERT_EQ(a.at(x, y), b.at(x, y))
                << "frame at " << seconds << " s, pixel " << x << ", " << y;
}

TEST(GltfSequence, FramesPreparedByRefittingRenderAsFramesPreparedAnew) {
    for (double shutter : {0.0, 0.05}) {
        AssetCache assets;
        FrameAccel accel;
        int refitted = 0;
        for (double seconds : {0.0, 0.25, 0.5, 1.0, 2.0}) {
            std::unique_ptr<Scene> sequence = frameAt(seconds, shutter, assets);
            sequence->prepare({.reuse = &accel, .refitGrowth = 1e9});
            EXPECT_FALSE(accel.kept);  // taken
            refitted += sequence->bvh().stats().refitted;
            std::unique_ptr<Scene> alone = frameAt(seconds, shutter, assets);
            alone->prepare();
            EXPECT_FALSE(alone->bvh().stats().refitted);
            expectSameImage(renderFrame(*sequence), renderFrame(*alone), seconds);
            sequence->keepAccel(accel);
            EXPECT_TRUE(accel.kept);
            EXPECT_FALSE(sequence->prepared());
        }
        EXPECT_EQ(refitted, 4) << "shutter " << shutter;  // every frame after the first
    }
}

TEST(GltfSequence, ATreeGrownPastTheLimitIsBuiltAnew) {
    AssetCache assets;
    FrameAccel accel;
    std::unique_ptr<Scene> first = frameAt(0, 0, assets);
    first->prepare();
    first->keepAccel(accel);
    // A limit no tree meets: the next frame is built anew.
    std::unique_ptr<Scene> next = frameAt(1, 0, assets);
    next->prepare({.reuse = &accel, .refitGrowth = 0.5});
    EXPECT_FALSE(next->bvh().stats().refitted);
    // Nothing kept: built.
    std::unique_ptr<Scene> again = frameAt(1, 0, assets);
    again->prepare({.reuse = &accel});
    EXPECT_FALSE(again->bvh().stats().refitted);
}

}  // namespace
}  // namespace glint
