#include "glint/io/gltf/gltf_extensions.h"

#include <set>

#include "glint/io/gltf/gltf_internal.h"
#include "glint/io/image/texture_io.h"

namespace glint {

const GltfExtension* findGltfExtension(std::string_view name) {
    // A build without a WebP decoder (the web page's) says so of EXT_texture_webp.
    static constexpr GltfExtension kNoWebp{
        "EXT_texture_webp", GltfSupport::Ignored,
        "this build does not decode WebP images, so a texture shows its fallback image, or its "
        "material's factors where it has none"};
    if (name == kNoWebp.name && !decodesWebp()) return &kNoWebp;
    for (const GltfExtension& e : kGltfExtensions)
        if (e.name == name) return &e;
    return nullptr;
}

bool rendersGltfExtension(std::string_view name) {
    const GltfExtension* e = findGltfExtension(name);
    return e && (e->support == GltfSupport::Rendered || e->support == GltfSupport::Partly ||
                 e->support == GltfSupport::Metadata);
}

std::string gltfSupportText(std::string_view name) {
    const GltfExtension* e = findGltfExtension(name);
    if (!e) return "ignored: " + std::string(kUnknownGltfNote);
    switch (e->support) {
        case GltfSupport::Rendered:
            return "rendered";
        case GltfSupport::Partly:
            return "partly: " + std::string(e->note);
        case GltfSupport::Metadata:
            return "metadata: nothing to render";
        case GltfSupport::Ignored:
            break;
    }
    return "ignored: " + std::string(e->note);
}

}  // namespace glint

namespace glint::gltf {
namespace {

/// Texture infos and other objects inside extension objects may carry extensions of their own
/// (a clear coat texture's KHR_texture_transform): they are looked for this deep.
constexpr int kMaxNesting = 16;

void addNested(const tinygltf::Value& v, std::set<std::string>& out, int depth);

void addAll(const tinygltf::ExtensionMap& extensions, std::set<std::string>& out, int depth = 0) {
    for (const auto& [name, value] : extensions) {
        out.insert(name);
        addNested(value, out, depth + 1);
    }
}

void addNested(const tinygltf::Value& v, std::set<std::string>& out, int depth) {
    if (depth > kMaxNesting) return;
    if (v.IsArray()) {
        for (size_t i = 0; i < v.ArrayLen(); ++i)
            addNested(v.Get(static_cast<int>(i)), out, depth + 1);
        return;
    }
    if (!v.IsObject()) return;
    for (const std::string& key : v.Keys()) {
        const tinygltf::Value& x = v.Get(key);
        if (key == "extensions" && x.IsObject()) {
            for (const std::string& name : x.Keys()) {
                out.insert(name);
                addNested(x.Get(name), out, depth + 1);
            }
        } else {
            addNested(x, out, depth + 1);
        }
    }
}

/// Every extension name the file uses: those it declares, and those on its objects.
std::set<std::string> namesUsed(const tinygltf::Model& m) {
    std::set<std::string> out(m.extensionsUsed.begin(), m.extensionsUsed.end());
    out.insert(m.extensionsRequired.begin(), m.extensionsRequired.end());
    addAll(m.extensions, out);
    auto each = [&](const auto& objects) {
        for (const auto& o : objects) addAll(o.extensions, out);
    };
    each(m.scenes);
    each(m.nodes);
    each(m.meshes);
    for (const tinygltf::Mesh& mesh : m.meshes) each(mesh.primitives);
    each(m.materials);
    for (const tinygltf::Material& mat : m.materials) {
        const tinygltf::PbrMetallicRoughness& pbr = mat.pbrMetallicRoughness;
        addAll(pbr.extensions, out);
        addAll(pbr.baseColorTexture.extensions, out);
        addAll(pbr.metallicRoughnessTexture.extensions, out);
        addAll(mat.normalTexture.extensions, out);
        addAll(mat.occlusionTexture.extensions, out);
        addAll(mat.emissiveTexture.extensions, out);
    }
    each(m.textures);
    each(m.images);
    each(m.samplers);
    each(m.buffers);
    each(m.bufferViews);
    each(m.accessors);
    each(m.cameras);
    each(m.lights);
    each(m.skins);
    each(m.animations);
    return out;
}

}  // namespace

std::vector<FormatExtension> reportExtensions(Context& ctx) {
    std::vector<FormatExtension> out;
    for (const std::string& name : namesUsed(ctx.model)) {
        const GltfExtension* e = findGltfExtension(name);
        if (!e || e->support == GltfSupport::Ignored)
            ctx.warn("the file uses " + name + ", which Glint does not render: " +
                     std::string(e ? e->note : kUnknownGltfNote));
        out.push_back({name, gltfSupportText(name)});
    }
    return out;
}

}  // namespace glint::gltf
