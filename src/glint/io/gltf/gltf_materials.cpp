// glTF metallic-roughness materials as Glint materials (docs/scene-format.md, "glTF materials"),
// and the images their textures use, decoded by Glint's texture reader.

#include <algorithm>
#include <cmath>

#include "glint/io/gltf/gltf_internal.h"
#include "glint/io/obj/obj_loader.h"
#include "glint/io/image/texture_io.h"

namespace glint::gltf {
namespace {

/// Reflectance at normal incidence of glTF's dielectrics (an index of refraction of 1.5).
constexpr double kDielectricF0 = 0.04;
/// Blinn-Phong exponent for roughness 0, where Glint's specular term is the course's: a
/// highlight as small as a mirror's image of a light.
constexpr double kSmoothShininess = 1000;

double unit(double x) { return std::clamp(x, 0.0, 1.0); }

/// A number of a glTF extension object, `fallback` when absent. Present but not a finite
/// number is an error.
double extensionNumber(const Context& ctx, const tinygltf::ExtensionMap& extensions,
                       const char* extension, const char* key, double fallback,
                       const std::string& label) {
    auto it = extensions.find(extension);
    if (it == extensions.end() || !it->second.IsObject() || !it->second.Has(key)) return fallback;
    const tinygltf::Value& v = it->second.Get(key);
    double x = v.IsNumber() ? v.GetNumberAsDouble() : NAN;
    if (!std::isfinite(x))
        ctx.fail(label + ": " + extension + " " + key + " must be a finite number");
    return x;
}

/// "%" escapes of a URI decoded ("my%20file.png" -> "my file.png").
std::string percentDecoded(const std::string& uri) {
    std::string out;
    for (size_t i = 0; i < uri.size(); ++i) {
        auto hex = [](char c) {
            return c >= '0' && c <= '9'   ? c - '0'
                   : c >= 'a' && c <= 'f' ? c - 'a' + 10
                   : c >= 'A' && c <= 'F' ? c - 'A' + 10
                                          : -1;
        };
        if (uri[i] == '%' && i + 2 < uri.size() && hex(uri[i + 1]) >= 0 && hex(uri[i + 2]) >= 0) {
            out += static_cast<char>(hex(uri[i + 1]) * 16 + hex(uri[i + 2]));
            i += 2;
        } else {
            out += uri[i];
        }
    }
    return out;
}

}  // namespace

const MeshMaterial& Materials::get(int index) {
    auto it = mapped_.find(index);
    if (it == mapped_.end()) it = mapped_.emplace(index, map(index)).first;
    return it->second;
}

MeshMaterial Materials::map(int index) {
    const tinygltf::Material& m = ctx_.model.materials[static_cast<size_t>(index)];
    const std::string label = describe("material", static_cast<size_t>(index), m.name);
    const tinygltf::PbrMetallicRoughness& pbr = m.pbrMetallicRoughness;
    auto numbers = [&](const std::vector<double>& v, size_t n, const char* what) {
        if (v.size() != n)
            ctx_.fail(label + ": " + what + " must have " + std::to_string(n) + " numbers, got " +
                      std::to_string(v.size()));
        for (double x : v)
            if (!std::isfinite(x)) ctx_.fail(label + ": " + what + " must be finite numbers");
        return v;
    };
    const std::vector<double> b = pbr.baseColorFactor.empty()
                                      ? std::vector<double>{1, 1, 1, 1}
                                      : numbers(pbr.baseColorFactor, 4, "baseColorFactor");
    const std::vector<double> e = m.emissiveFactor.empty()
                                      ? std::vector<double>{0, 0, 0}
                                      : numbers(m.emissiveFactor, 3, "emissiveFactor");
    if (!std::isfinite(pbr.metallicFactor) || !std::isfinite(pbr.roughnessFactor) ||
        !std::isfinite(m.alphaCutoff))
        ctx_.fail(label + ": metallicFactor, roughnessFactor and alphaCutoff must be finite");
    // glTF's factors lie in [0, 1]; values outside are clamped.
    const Vec3 base(unit(b[0]), unit(b[1]), unit(b[2]));
    const double alpha = unit(b[3]);
    double metallic = unit(pbr.metallicFactor), roughness = unit(pbr.roughnessFactor);

    MeshMaterial out;
    out.name = m.name.empty() ? label : m.name;
    TextureWrap wrap = TextureWrap::Repeat;
    std::shared_ptr<const TextureImage> baseImage =
        slotImage(pbr.baseColorTexture, label, "baseColorTexture", true,
                  "its faces show its base colour factor instead", &wrap);
    // Textures Glint cannot vary over the surface count with their mean value.
    if (auto mr = slotImage(pbr.metallicRoughnessTexture, label, "metallicRoughnessTexture", false,
                            "its metallic and roughness factors are used alone")) {
        Vec3 mean = mr->average();
        roughness *= mean.y;  // glTF: roughness in green, metalness in blue
        metallic *= mean.z;
    }
    double strength = extensionNumber(ctx_, m.extensions, "KHR_materials_emissive_strength",
                                      "emissiveStrength", 1, label);
    if (strength < 0) ctx_.fail(label + ": emissiveStrength must not be negative");
    Vec3 emission = Vec3(unit(e[0]), unit(e[1]), unit(e[2])) * strength;
    if (!(emission == Vec3(0)))
        if (auto em = slotImage(m.emissiveTexture, label, "emissiveTexture", true,
                                "its emissive factor is used alone"))
            emission = emission * em->average();

    // How much light passes through: alpha blending (straight through), and the specular
    // transmission of KHR_materials_transmission (refracted), for the dielectric part.
    double opacity = 1;
    if (m.alphaMode == "BLEND") {
        opacity = alpha;
    } else if (m.alphaMode == "MASK") {
        opacity = alpha >= m.alphaCutoff ? 1 : 0;
    } else if (m.alphaMode != "OPAQUE") {
        ctx_.warn(label + ": alphaMode '" + m.alphaMode + "' is not one glTF defines: opaque");
    }
    if (baseImage && m.alphaMode != "OPAQUE")
        ctx_.warnOnce("texture-alpha",
                      "the alpha channel of base colour textures is not read: alphaMode BLEND and "
                      "MASK use the alpha of baseColorFactor only");
    const bool transmissive = m.extensions.count("KHR_materials_transmission") > 0;
    const double transmission = unit(extensionNumber(
        ctx_, m.extensions, "KHR_materials_transmission", "transmissionFactor", 0, label));
    double ior = extensionNumber(ctx_, m.extensions, "KHR_materials_ior", "ior", 1.5, label);
    if (!(ior >= 1)) ior = 1.5;  // glTF allows 0 (and nothing else below 1) for "unknown"

    Material& g = out.material;
    const Vec3 baseMean = baseImage ? base * baseImage->average() : base;
    g.diffuse = base * ((1 - metallic) * (1 - transmission) * opacity);
    // Alpha blending weighs the whole surface (its reflection and emission too) by opacity.
    g.specular = (Vec3(kDielectricF0 * (1 - metallic)) + baseMean * metallic) * opacity;
    g.roughness = roughness * roughness;  // glTF's perceptual roughness squared is GGX's alpha
    g.shininess = kSmoothShininess;       // used only where the roughness is 0
    g.emission = emission * opacity;
    g.transmission = base * (transmission * (1 - metallic) * opacity) + Vec3(1 - opacity);
    g.ior = transmissive ? ior : 1;
    // Ambient light as for MTL materials without Ka: a dim version of the surface's colour.
    g.ambient = (baseImage ? g.diffuse * baseImage->average() : g.diffuse) * kMtlAmbientLight;
    if (baseImage) {
        Texture t;
        t.kind = Texture::Kind::Image;
        t.wrap = wrap;
        t.image = baseImage;
        t.a = g.diffuse;  // the texel times the factor, where Glint's diffuse colour goes
        out.texture = t;
    }
    return out;
}

std::shared_ptr<const TextureImage> Materials::slotImage(const tinygltf::TextureInfo& info,
                                                         const std::string& material,
                                                         const char* slot, bool srgb,
                                                         const char* instead, TextureWrap* wrap) {
    if (info.index == -1) return nullptr;
    const std::string user = material + " " + slot;
    const auto& textures = ctx_.model.textures;
    if (info.index < 0 || static_cast<size_t>(info.index) >= textures.size())
        missing(ctx_, "texture", info.index, textures.size(), user);
    const tinygltf::Texture& texture = textures[static_cast<size_t>(info.index)];
    if (info.texCoord != 0) {
        ctx_.warn(material + ": its " + slot + " uses TEXCOORD_" + std::to_string(info.texCoord) +
                  ", and Glint reads TEXCOORD_0 only: " + instead);
        return nullptr;
    }
    if (info.extensions.count("KHR_texture_transform"))
        ctx_.warnOnce("texture-transform",
                      "KHR_texture_transform is not supported: textures are applied as if "
                      "untransformed");
    if (texture.source == -1) {
        ctx_.warn(material + ": " + describe("texture", static_cast<size_t>(info.index), "") +
                  " has no image Glint reads (no 'source'): " + instead);
        return nullptr;
    }
    const auto& images = ctx_.model.images;
    if (texture.source < 0 || static_cast<size_t>(texture.source) >= images.size())
        missing(ctx_, "image", texture.source, images.size(),
                "texture " + std::to_string(info.index));
    if (wrap && texture.sampler != -1) {
        const auto& samplers = ctx_.model.samplers;
        if (texture.sampler < 0 || static_cast<size_t>(texture.sampler) >= samplers.size())
            missing(ctx_, "sampler", texture.sampler, samplers.size(),
                    "texture " + std::to_string(info.index));
        const tinygltf::Sampler& s = samplers[static_cast<size_t>(texture.sampler)];
        const bool clampS = s.wrapS == TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE;
        const bool clampT = s.wrapT == TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE;
        *wrap = clampS && clampT ? TextureWrap::Clamp : TextureWrap::Repeat;
        if (s.wrapS == TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT ||
            s.wrapT == TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT)
            ctx_.warnOnce("mirrored", "MIRRORED_REPEAT wrapping is approximated by REPEAT");
        if (clampS != clampT)
            ctx_.warnOnce("wrap",
                          "textures that clamp along one axis and repeat along the other "
                          "repeat along both");
    }
    std::string problem;
    std::shared_ptr<const TextureImage> img = image(texture.source, srgb, problem);
    if (!img) ctx_.warn(material + ": " + problem + "; " + instead);
    return img;
}

std::shared_ptr<const TextureImage> Materials::image(int index, bool srgb, std::string& problem) {
    auto [it, added] = images_.emplace(std::make_pair(index, srgb), Decoded{});
    Decoded& d = it->second;
    if (added) {
        const tinygltf::Image& im = ctx_.model.images[static_cast<size_t>(index)];
        const std::string name = "image " + std::to_string(index);
        const LoadLimits& limits = ctx_.options.limits;
        try {
            if (im.bufferView != -1) {
                std::string_view bytes = bufferViewBytes(ctx_, im.bufferView, name);
                d.image = decodeTextureImage(bytes, name, srgb, limits);
            } else if (im.as_is) {  // a data: URI, decoded by tinygltf
                std::string_view bytes(reinterpret_cast<const char*>(im.image.data()),
                                       im.image.size());
                d.image = decodeTextureImage(bytes, name, srgb, limits);
            } else if (!im.uri.empty()) {
                std::string uri = percentDecoded(im.uri);
                std::string path =
                    uri.front() == '/' || ctx_.dir.empty() ? uri : ctx_.dir + "/" + uri;
                if (!limits.readFiles)
                    d.problem = "texture '" + path + "' is not read: reading files is off";
                else
                    d.image = loadTextureImage(path, srgb, limits);
            } else {
                d.problem = name + " has neither a URI nor a bufferView";
            }
        } catch (const RenderError& e) {
            d.problem = e.what();
        }
    }
    problem = d.problem;
    return d.image;
}

}  // namespace glint::gltf
