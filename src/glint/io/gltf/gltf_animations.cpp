// glTF animations (glTF 2.0, section 3.11): listing them, and playing one at a time into the
// values of the nodes it moves (Context::animated). The nodes are then walked as usual: their
// transforms, the skins' joints and the morph weights read what the animation gave them.

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <optional>

#include "glint/io/gltf/gltf_internal.h"
#include "glint/scene/keyframes.h"

namespace glint::gltf {
namespace {

/// "0 = 'Walk' (0 to 2.2 s), 1 = animation 1 (0 to 1 s)": what --animation may name.
std::string animationList(const std::vector<ModelAnimation>& animations) {
    if (animations.empty()) return "the file has no animations";
    std::string s = "the file has " + std::to_string(animations.size()) +
                    (animations.size() == 1 ? " animation: " : " animations: ");
    constexpr size_t kListed = 20;
    for (size_t i = 0; i < animations.size() && i < kListed; ++i) {
        char range[64];
        std::snprintf(range, sizeof range, " (%g to %g s)", animations[i].start, animations[i].end);
        s += (i ? ", " : "") + std::to_string(i) + " = " +
             (animations[i].name.empty() ? "unnamed" : "'" + animations[i].name + "'") + range;
    }
    if (animations.size() > kListed) s += ", ...";
    return s;
}

/// The animation `name` chooses: an index, or a name; empty for the first (none when the file
/// has none: it is still).
std::optional<size_t> chooseAnimation(const Context& ctx, const std::string& name) {
    const auto& animations = ctx.model.animations;
    if (name.empty()) return animations.empty() ? std::nullopt : std::optional<size_t>(0);
    size_t index = 0;
    auto [p, ec] = std::from_chars(name.data(), name.data() + name.size(), index);
    if (ec == std::errc() && p == name.data() + name.size()) {
        if (index < animations.size()) return index;
        ctx.fail("there is no animation " + name +
                 " (animations are numbered from 0): " + animationList(listAnimations(ctx)));
    }
    for (size_t i = 0; i < animations.size(); ++i)
        if (animations[i].name == name) return i;
    ctx.fail("no animation is named '" + name + "': " + animationList(listAnimations(ctx)));
}

/// The number of morph targets of node `node`'s mesh (0 without one).
size_t targetsOf(const Context& ctx, int node) {
    const int mesh = ctx.model.nodes[static_cast<size_t>(node)].mesh;
    if (mesh < 0 || static_cast<size_t>(mesh) >= ctx.model.meshes.size()) return 0;
    return morphTargetCount(ctx, mesh);
}

}  // namespace

std::vector<ModelAnimation> listAnimations(const Context& ctx) {
    std::vector<ModelAnimation> out;
    for (const tinygltf::Animation& a : ctx.model.animations) {
        ModelAnimation m;
        m.name = a.name;
        m.channels = a.channels.size();
        bool any = false;
        for (const tinygltf::AnimationSampler& s : a.samplers) {
            if (s.input < 0 || static_cast<size_t>(s.input) >= ctx.model.accessors.size()) continue;
            const tinygltf::Accessor& input = ctx.model.accessors[static_cast<size_t>(s.input)];
            double lo = 0, hi = 0;
            if (input.minValues.size() == 1 && input.maxValues.size() == 1) {
                lo = input.minValues[0];
                hi = input.maxValues[0];
            } else {
                // glTF requires min and max of key times; a file without them is read.
                try {
                    const FloatElements times = readFloats(ctx, s.input, "input", false);
                    if (times.values.empty()) continue;
                    lo = *std::min_element(times.values.begin(), times.values.end());
                    hi = *std::max_element(times.values.begin(), times.values.end());
                } catch (const SceneError&) {
                    continue;  // said when the animation is played
                }
            }
            if (!std::isfinite(lo) || !std::isfinite(hi) || lo > hi) continue;
            m.start = any ? std::min(m.start, lo) : lo;
            m.end = any ? std::max(m.end, hi) : hi;
            any = true;
        }
        out.push_back(m);
    }
    return out;
}

std::optional<size_t> playAnimation(Context& ctx, const ModelTime& time, std::string& played) {
    const std::optional<size_t> chosen = chooseAnimation(ctx, time.animation);
    if (!chosen) return std::nullopt;
    const size_t index = *chosen;
    const tinygltf::Animation& a = ctx.model.animations[index];
    const std::string label = describe("animation", index, a.name);
    const double t = *time.seconds;
    if (!std::isfinite(t)) ctx.fail(label + ": the time to play it at must be finite");
    const auto& nodes = ctx.model.nodes;
    ctx.animated.assign(nodes.size(), {});
    for (size_t c = 0; c < a.channels.size(); ++c) {
        const tinygltf::AnimationChannel& ch = a.channels[c];
        const std::string channel = label + ", channel " + std::to_string(c);
        if (ch.target_node == -1) continue;  // a target of an extension (KHR_animation_pointer)
        if (ch.target_node < 0 || static_cast<size_t>(ch.target_node) >= nodes.size())
            missing(ctx, "node", ch.target_node, nodes.size(), channel);
        const size_t node = static_cast<size_t>(ch.target_node);
        const std::string& path = ch.target_path;
        const bool weights = path == "weights", rotation = path == "rotation";
        if (!weights && !rotation && path != "translation" && path != "scale") {
            ctx.warnOnce("path " + path, channel + ": target path '" + path +
                                             "' is not one glTF defines: the channel is ignored");
            continue;
        }
        if (!nodes[node].matrix.empty())
            ctx.fail(channel + ": it animates " + describe("node", node, nodes[node].name) +
                     ", which has a matrix (glTF animates translation, rotation and scale only)");
        if (ch.sampler < 0 || static_cast<size_t>(ch.sampler) >= a.samplers.size())
            ctx.fail(channel + ": sampler " + std::to_string(ch.sampler) +
                     " does not exist (the animation has " + std::to_string(a.samplers.size()) +
                     " samplers)");
        const tinygltf::AnimationSampler& s = a.samplers[static_cast<size_t>(ch.sampler)];
        const std::string sampler = label + ", sampler " + std::to_string(ch.sampler);

        KeyframeTrack track;
        track.rotation = rotation;
        if (s.interpolation == "STEP")
            track.interpolation = Interpolation::Step;
        else if (s.interpolation == "CUBICSPLINE")
            track.interpolation = Interpolation::CubicSpline;
        else if (s.interpolation == "LINEAR" || s.interpolation.empty())
            track.interpolation = Interpolation::Linear;
        else
            ctx.fail(sampler + ": interpolation '" + s.interpolation +
                     "' is not LINEAR, STEP or CUBICSPLINE");
        const FloatElements input = readFloats(ctx, s.input, "input of " + sampler, false);
        if (input.components != 1) ctx.fail(input.label + ": key times must be SCALAR");
        // Rotations and weights may be normalised integers; translations and scales are floats.
        const FloatElements output =
            readFloats(ctx, s.output, "output of " + sampler, rotation || weights);
        const size_t expected = weights ? 1 : rotation ? 4 : 3;
        if (output.components != expected)
            ctx.fail(output.label + ": a " + path + " needs " + std::to_string(expected) +
                     (expected == 1 ? " component" : " components") + " per element, it has " +
                     std::to_string(output.components));
        track.times.assign(input.values.begin(), input.values.end());
        track.values.assign(output.values.begin(), output.values.end());
        const size_t perKey = track.interpolation == Interpolation::CubicSpline ? 3 : 1;
        // Weights: one per morph target of the node's mesh, for each key.
        const size_t targets = weights ? targetsOf(ctx, ch.target_node) : 1;
        if (targets == 0)
            ctx.fail(channel + ": it animates the morph weights of " +
                     describe("node", node, nodes[node].name) +
                     ", whose mesh has no morph targets");
        track.width = weights ? targets : expected;
        if (output.count != input.count * perKey * targets) {
            std::string why;
            if (weights) why = std::to_string(targets) + " morph weights per key";
            if (perKey == 3) why += (why.empty() ? "" : ", ") + std::string("with tangents");
            ctx.fail(sampler + ": it has " + std::to_string(input.count) + " key times and " +
                     std::to_string(output.count) + " output values, not " +
                     std::to_string(input.count * perKey * targets) +
                     (why.empty() ? "" : " (" + why + ")"));
        }
        if (std::string problem = track.problem(); !problem.empty())
            ctx.fail(sampler + " (" + path + " of " + describe("node", node, nodes[node].name) +
                     "): " + problem);
        AnimatedNode& out = ctx.animated[node];
        if (weights) {
            out.weights.emplace(track.width);
            track.sample(t, out.weights->data());
        } else if (rotation) {
            out.rotation.emplace();
            track.sample(t, out.rotation->data());
        } else {
            auto& v = path == "translation" ? out.translation : out.scale;
            v.emplace();
            track.sample(t, v->data());
        }
    }
    char at[48];
    std::snprintf(at, sizeof at, " at %g s", t);
    played = label + at;
    return index;
}

}  // namespace glint::gltf
