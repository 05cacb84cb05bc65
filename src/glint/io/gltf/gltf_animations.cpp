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

/// Within JSON object `v`, the number or array of `width` numbers that `keys` lead to: read
/// into `get` (absent: 0, or 1s for an array), written from `set`. False when the way is not
/// objects or the value is neither.
bool valueTarget(tinygltf::Value& v, const std::vector<std::string>& keys, size_t at, size_t width,
                 std::vector<double>* get, const std::vector<double>* set) {
    if (!v.IsObject() || at >= keys.size()) return false;
    tinygltf::Value::Object object = v.Get<tinygltf::Value::Object>();
    auto it = object.find(keys[at]);
    if (at + 1 < keys.size()) {
        if (it == object.end() || !valueTarget(it->second, keys, at + 1, width, get, set))
            return false;
    } else {
        if (it != object.end() && !it->second.IsNumber() && !it->second.IsArray()) return false;
        if (get) {
            get->assign(width, width == 1 ? 0.0 : 1.0);  // absent: the usual defaults
            if (it != object.end() && it->second.IsNumber() && width == 1)
                (*get)[0] = it->second.GetNumberAsDouble();
            if (it != object.end() && it->second.IsArray() && it->second.ArrayLen() == width)
                for (size_t k = 0; k < width; ++k)
                    (*get)[k] = it->second.Get(static_cast<int>(k)).GetNumberAsDouble();
        }
        if (!set) return true;
        if (width == 1) {
            object[keys[at]] = tinygltf::Value((*set)[0]);
        } else {
            tinygltf::Value::Array a;
            for (double x : *set) a.push_back(tinygltf::Value(x));
            object[keys[at]] = tinygltf::Value(std::move(a));
        }
    }
    if (set) v = tinygltf::Value(std::move(object));
    return true;
}

/// The property of ctx.model that JSON pointer `pointer` (KHR_animation_pointer) names, read
/// and written as `width` numbers: `get` its value, `set` a new one. Material factors and the
/// numbers and colours of material extensions, punctual lights' colour, intensity, range and
/// cone, and perspective cameras' fields. False for any other target, or a width the target
/// does not take. `material` is set to the material it belongs to (else -1).
bool pointerTarget(Context& ctx, const std::string& pointer, size_t width, std::vector<double>* get,
                   const std::vector<double>* set, int& material) {
    std::vector<std::string> part;
    for (size_t at = 1; at <= pointer.size() && !pointer.empty() && pointer[0] == '/';) {
        const size_t end = std::min(pointer.find('/', at), pointer.size());
        part.push_back(pointer.substr(at, end - at));
        at = end + 1;
    }
    auto index = [&](const std::string& s, size_t count) -> std::optional<size_t> {
        size_t i = 0;
        auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), i);
        if (ec != std::errc() || p != s.data() + s.size() || i >= count) return std::nullopt;
        return i;
    };
    // A number or a fixed-size array of numbers, with its default where the file has none.
    auto number = [&](double& v) {
        if (width != 1) return false;
        if (get) *get = {v};
        if (set) v = (*set)[0];
        return true;
    };
    auto numbers = [&](std::vector<double>& v, std::vector<double> fallback) {
        if (width != fallback.size()) return false;
        if (get) *get = v.size() == width ? v : fallback;
        if (set) v = *set;
        return true;
    };
    material = -1;
    const size_t n = part.size();
    if (n >= 3 && part[0] == "materials") {
        const auto m = index(part[1], ctx.model.materials.size());
        if (!m) return false;
        material = static_cast<int>(*m);
        tinygltf::Material& mat = ctx.model.materials[*m];
        if (n == 4 && part[2] == "pbrMetallicRoughness") {
            auto& pbr = mat.pbrMetallicRoughness;
            if (part[3] == "baseColorFactor") return numbers(pbr.baseColorFactor, {1, 1, 1, 1});
            if (part[3] == "metallicFactor") return number(pbr.metallicFactor);
            if (part[3] == "roughnessFactor") return number(pbr.roughnessFactor);
            return false;
        }
        if (n == 3 && part[2] == "emissiveFactor") return numbers(mat.emissiveFactor, {0, 0, 0});
        if (n == 3 && part[2] == "alphaCutoff") return number(mat.alphaCutoff);
        // A number or colour of a material extension, however deep (a texture's transform).
        auto inExtensions = [&](tinygltf::ExtensionMap& map, size_t at) {
            auto ext = map.find(part[at]);
            if (ext == map.end()) return false;
            return valueTarget(ext->second, part, at + 1, width, get, set);
        };
        if (n >= 5 && part[2] == "extensions") return inExtensions(mat.extensions, 3);
        // The core textures: a normal map's scale, an occlusion map's strength, and each one's
        // KHR_texture_transform (offset, scale, rotation).
        tinygltf::ExtensionMap* textureExtensions = nullptr;
        size_t next = 3;
        if (part[2] == "normalTexture") {
            if (n == 4 && part[3] == "scale") return number(mat.normalTexture.scale);
            textureExtensions = &mat.normalTexture.extensions;
        } else if (part[2] == "occlusionTexture") {
            if (n == 4 && part[3] == "strength") return number(mat.occlusionTexture.strength);
            textureExtensions = &mat.occlusionTexture.extensions;
        } else if (part[2] == "emissiveTexture") {
            textureExtensions = &mat.emissiveTexture.extensions;
        } else if (part[2] == "pbrMetallicRoughness" && n >= 4) {
            next = 4;
            if (part[3] == "baseColorTexture")
                textureExtensions = &mat.pbrMetallicRoughness.baseColorTexture.extensions;
            else if (part[3] == "metallicRoughnessTexture")
                textureExtensions = &mat.pbrMetallicRoughness.metallicRoughnessTexture.extensions;
        }
        if (textureExtensions && n >= next + 3 && part[next] == "extensions")
            return inExtensions(*textureExtensions, next + 1);
        return false;
    }
    if (n >= 5 && part[0] == "extensions" && part[1] == "KHR_lights_punctual" &&
        part[2] == "lights") {
        const auto l = index(part[3], ctx.model.lights.size());
        if (!l) return false;
        tinygltf::Light& light = ctx.model.lights[*l];
        if (n == 5 && part[4] == "color") return numbers(light.color, {1, 1, 1});
        if (n == 5 && part[4] == "intensity") return number(light.intensity);
        if (n == 5 && part[4] == "range") return number(light.range);
        if (n == 6 && part[4] == "spot" && part[5] == "innerConeAngle")
            return number(light.spot.innerConeAngle);
        if (n == 6 && part[4] == "spot" && part[5] == "outerConeAngle")
            return number(light.spot.outerConeAngle);
        return false;
    }
    if (n == 4 && part[0] == "cameras" && part[2] == "perspective") {
        const auto c = index(part[1], ctx.model.cameras.size());
        if (!c) return false;
        tinygltf::PerspectiveCamera& p = ctx.model.cameras[*c].perspective;
        if (part[3] == "yfov") return number(p.yfov);
        if (part[3] == "aspectRatio") return number(p.aspectRatio);
        if (part[3] == "znear") return number(p.znear);
        if (part[3] == "zfar") return number(p.zfar);
    }
    return false;
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

namespace {

/// The sampler of channel `ch` (named `channel`) of animation `a`; fails if there is none.
const tinygltf::AnimationSampler& samplerOf(const Context& ctx, const tinygltf::Animation& a,
                                            const tinygltf::AnimationChannel& ch,
                                            const std::string& channel) {
    if (ch.sampler < 0 || static_cast<size_t>(ch.sampler) >= a.samplers.size())
        ctx.fail(channel + ": sampler " + std::to_string(ch.sampler) +
                 " does not exist (the animation has " + std::to_string(a.samplers.size()) +
                 " samplers)");
    return a.samplers[static_cast<size_t>(ch.sampler)];
}

/// Sampler `s`'s interpolation (named `sampler` in the message when glTF has no such one).
Interpolation interpolationOf(const Context& ctx, const tinygltf::AnimationSampler& s,
                              const std::string& sampler) {
    if (s.interpolation == "STEP") return Interpolation::Step;
    if (s.interpolation == "CUBICSPLINE") return Interpolation::CubicSpline;
    if (s.interpolation != "LINEAR" && !s.interpolation.empty())
        ctx.fail(sampler + ": interpolation '" + s.interpolation +
                 "' is not LINEAR, STEP or CUBICSPLINE");
    return Interpolation::Linear;
}

/// The sampler of channel `ch` of animation `a` for `width` numbers per key.
KeyframeTrack trackOf(Context& ctx, const tinygltf::Animation& a,
                      const tinygltf::AnimationChannel& ch, const std::string& label,
                      size_t width) {
    const tinygltf::AnimationSampler& s = samplerOf(ctx, a, ch, label);
    KeyframeTrack track;
    track.interpolation = interpolationOf(ctx, s, label);
    const FloatElements input = readFloats(ctx, s.input, "input of " + label, false);
    const FloatElements output = readFloats(ctx, s.output, "output of " + label, false);
    const size_t perKey = track.interpolation == Interpolation::CubicSpline ? 3 : 1;
    if (input.components != 1 || output.components != width || output.count != input.count * perKey)
        ctx.fail(label + ": its sampler's keys do not match its target (" + std::to_string(width) +
                 " numbers per key)");
    track.times.assign(input.values.begin(), input.values.end());
    track.values.assign(output.values.begin(), output.values.end());
    track.width = width;
    if (std::string problem = track.problem(); !problem.empty()) ctx.fail(label + ": " + problem);
    return track;
}

/// The JSON pointer of KHR_animation_pointer channel `ch`; none for another kind of channel.
std::optional<std::string> pointerOf(const tinygltf::AnimationChannel& ch) {
    const auto ext = ch.target_extensions.find("KHR_animation_pointer");
    if (ch.target_path != "pointer" || ext == ch.target_extensions.end() ||
        !ext->second.IsObject() || !ext->second.Has("pointer") ||
        !ext->second.Get("pointer").IsString())
        return std::nullopt;
    return ext->second.Get("pointer").Get<std::string>();
}

/// Whether pointer channel `ch` points at a node's translation, rotation, scale or weights:
/// then `out` is the node's channel it stands for.
bool nodePointer(const tinygltf::AnimationChannel& ch, tinygltf::AnimationChannel& out) {
    const std::optional<std::string> to = pointerOf(ch);
    if (!to) return false;
    const std::string& pointer = *to;
    const std::string prefix = "/nodes/";
    if (pointer.rfind(prefix, 0) != 0) return false;
    const size_t slash = pointer.find('/', prefix.size());
    if (slash == std::string::npos) return false;
    int node = -1;
    const char* first = pointer.data() + prefix.size();
    auto [p, ec] = std::from_chars(first, pointer.data() + slash, node);
    const std::string path = pointer.substr(slash + 1);
    if (ec != std::errc() || p != pointer.data() + slash || node < 0 ||
        (path != "translation" && path != "rotation" && path != "scale" && path != "weights"))
        return false;
    out = ch;
    out.target_node = node;
    out.target_path = path;
    return true;
}

/// Plays channel `ch` of animation `a` at time `t` if it is a KHR_animation_pointer channel:
/// sets its target in ctx.model, keeping what it was (Context::pointed).
void playPointer(Context& ctx, const tinygltf::Animation& a, const tinygltf::AnimationChannel& ch,
                 const std::string& label, double t) {
    const std::optional<std::string> to = pointerOf(ch);
    if (!to) return;  // another extension's target: reported with the extensions
    const std::string& pointer = *to;
    // The sampler's output type gives the width: SCALAR 1, VEC3 3, VEC4 4.
    size_t width = 0;
    if (ch.sampler >= 0 && static_cast<size_t>(ch.sampler) < a.samplers.size()) {
        const int out = a.samplers[static_cast<size_t>(ch.sampler)].output;
        if (out >= 0 && static_cast<size_t>(out) < ctx.model.accessors.size())
            width = static_cast<size_t>(tinygltf::GetNumComponentsInType(
                ctx.model.accessors[static_cast<size_t>(out)].type));
    }
    std::vector<double> before;
    int material = -1;
    if (width == 0 || !pointerTarget(ctx, pointer, width, &before, nullptr, material)) {
        ctx.warnOnce("pointer " + pointer,
                     label + ": KHR_animation_pointer target '" + pointer +
                         "' is not played (Glint plays nodes' transforms and weights, "
                         "materials' factors, texture transforms and extensions' numbers, "
                         "punctual lights and perspective cameras)");
        return;
    }
    const KeyframeTrack track = trackOf(ctx, a, ch, label, width);
    std::vector<double> value(width);
    track.sample(t, value.data());
    ctx.pointed.emplace_back(pointer, before);
    pointerTarget(ctx, pointer, width, nullptr, &value, material);
    if (material >= 0) ctx.pointedMaterials.insert(material);
}

}  // namespace

void unplayPointers(Context& ctx) {
    // In reverse, so that a property set twice gets its first value back.
    for (auto it = ctx.pointed.rbegin(); it != ctx.pointed.rend(); ++it) {
        int material = -1;
        pointerTarget(ctx, it->first, it->second.size(), nullptr, &it->second, material);
    }
    ctx.pointed.clear();
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
        const std::string channel = label + ", channel " + std::to_string(c);
        // A pointer to a node's translation, rotation, scale or weights is played as the
        // channel of that node it stands for; other pointers set what they point to.
        tinygltf::AnimationChannel asNode;
        const tinygltf::AnimationChannel* use = &a.channels[c];
        if (use->target_node == -1) {  // KHR_animation_pointer, or another extension's target
            if (!nodePointer(*use, asNode)) {
                playPointer(ctx, a, *use, channel, t);
                continue;
            }
            use = &asNode;
        }
        const tinygltf::AnimationChannel& ch = *use;
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
        const tinygltf::AnimationSampler& s = samplerOf(ctx, a, ch, channel);
        const std::string sampler = label + ", sampler " + std::to_string(ch.sampler);

        KeyframeTrack track;
        track.rotation = rotation;
        track.interpolation = interpolationOf(ctx, s, sampler);
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
