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

std::vector<FormatExtension> reportExtensions(Context& ctx, const std::string& variant) {
    std::vector<FormatExtension> out;
    for (const std::string& name : namesUsed(ctx.model)) {
        const GltfExtension* e = findGltfExtension(name);
        if (!e || e->support == GltfSupport::Ignored)
            ctx.warn("the file uses " + name + ", which Glint does not render: " +
                     std::string(e ? e->note : kUnknownGltfNote));
        std::string text = gltfSupportText(name);
        if (name == "KHR_materials_variants") {
            const std::vector<std::string> names = materialVariants(ctx);
            text += ": ";
            for (size_t i = 0; i < names.size(); ++i)
                text += (i ? ", " : "") + std::to_string(i) + " '" + names[i] + "'";
            text += variant.empty() ? " (showing the file's own materials; --variant chooses)"
                                    : " (showing " + variant + ")";
        }
        out.push_back({name, text});
    }
    return out;
}

namespace {

/// The root object of KHR_materials_variants, or null.
const tinygltf::Value* variantsRoot(const Context& ctx) {
    auto it = ctx.model.extensions.find("KHR_materials_variants");
    if (it == ctx.model.extensions.end() || !it->second.IsObject()) return nullptr;
    const tinygltf::Value& list = it->second.Get("variants");
    return list.IsArray() ? &list : nullptr;
}

}  // namespace

std::vector<std::string> materialVariants(const Context& ctx) {
    std::vector<std::string> out;
    const tinygltf::Value* list = variantsRoot(ctx);
    if (!list) return out;
    for (size_t i = 0; i < list->ArrayLen(); ++i) {
        const tinygltf::Value& v = list->Get(static_cast<int>(i));
        const tinygltf::Value& name = v.IsObject() ? v.Get("name") : tinygltf::Value();
        out.push_back(name.IsString() ? name.Get<std::string>() : "variant " + std::to_string(i));
    }
    return out;
}

void applyVariant(Context& ctx, const std::string& variant) {
    if (variant.empty()) return;
    const std::vector<std::string> names = materialVariants(ctx);
    int chosen = -1;
    for (size_t i = 0; i < names.size() && chosen < 0; ++i)
        if (names[i] == variant) chosen = static_cast<int>(i);
    if (chosen < 0 && !variant.empty() &&
        variant.find_first_not_of("0123456789") == std::string::npos && variant.size() < 9 &&
        std::stoul(variant) < names.size())
        chosen = static_cast<int>(std::stoul(variant));
    if (chosen < 0) {
        std::string have = "the file has no material variants (KHR_materials_variants)";
        if (!names.empty()) {
            have = "its variants are";
            for (size_t i = 0; i < names.size(); ++i)
                have += (i ? ", " : " ") + std::to_string(i) + " '" + names[i] + "'";
        }
        ctx.fail("--variant " + variant + ": no such material variant: " + have);
    }
    const int materials = static_cast<int>(ctx.model.materials.size());
    for (tinygltf::Mesh& mesh : ctx.model.meshes)
        for (tinygltf::Primitive& p : mesh.primitives) {
            auto it = p.extensions.find("KHR_materials_variants");
            if (it == p.extensions.end() || !it->second.IsObject()) continue;
            const tinygltf::Value& mappings = it->second.Get("mappings");
            if (!mappings.IsArray()) continue;
            for (size_t m = 0; m < mappings.ArrayLen(); ++m) {
                const tinygltf::Value& map = mappings.Get(static_cast<int>(m));
                if (!map.IsObject() || !map.Get("material").IsInt()) continue;
                const int material = map.Get("material").Get<int>();
                const tinygltf::Value& variants = map.Get("variants");
                if (!variants.IsArray()) continue;
                for (size_t k = 0; k < variants.ArrayLen(); ++k) {
                    const tinygltf::Value& v = variants.Get(static_cast<int>(k));
                    if (!v.IsInt() || v.Get<int>() != chosen) continue;
                    if (material < 0 || material >= materials)
                        missing(ctx, "material", material, static_cast<size_t>(materials),
                                mesh.name.empty() ? "a mesh's variant" : mesh.name + "'s variant");
                    p.material = material;
                }
            }
        }
}

}  // namespace glint::gltf
