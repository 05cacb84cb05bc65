// glTF metallic-roughness materials as Glint materials (docs/scene-format.md, "glTF materials"),
// and the images their textures use, decoded by Glint's texture reader.

#include <algorithm>
#include <cmath>

#include "glint/io/gltf/gltf_internal.h"
#include "glint/io/image/texture_io.h"
#include "glint/io/obj/obj_loader.h"

namespace glint::gltf {
namespace {

/// Reflectance at normal incidence of glTF's dielectrics (an index of refraction of 1.5).
constexpr double kDielectricF0 = 0.04;
/// Blinn-Phong exponent for roughness 0, where Glint's specular term is the course's: a
/// highlight as small as a mirror's image of a light.
constexpr double kSmoothShininess = 1000;

double unit(double x) { return std::clamp(x, 0.0, 1.0); }

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
        !std::isfinite(m.alphaCutoff) || !std::isfinite(m.normalTexture.scale))
        ctx_.fail(label +
                  ": metallicFactor, roughnessFactor, alphaCutoff and the normal texture's scale "
                  "must be finite");
    // glTF's factors lie in [0, 1]; values outside are clamped.
    const Vec3 base(unit(b[0]), unit(b[1]), unit(b[2]));
    const double alpha = unit(b[3]);
    const double metallic = unit(pbr.metallicFactor), roughness = unit(pbr.roughnessFactor);

    MeshMaterial out;
    out.name = m.name.empty() ? label : m.name;
    PbrMaterial& p = out.pbr.emplace();
    p.baseColor = base;
    p.alpha = alpha;
    p.metallic = metallic;
    p.roughness = roughness;
    p.baseColorTexture = slot(pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord,
                              pbr.baseColorTexture.extensions, label, "baseColorTexture", true,
                              "its faces show its base colour factor instead");
    p.metallicRoughnessTexture =
        slot(pbr.metallicRoughnessTexture.index, pbr.metallicRoughnessTexture.texCoord,
             pbr.metallicRoughnessTexture.extensions, label, "metallicRoughnessTexture", false,
             "its metallic and roughness factors are used alone");
    p.normalTexture =
        slot(m.normalTexture.index, m.normalTexture.texCoord, m.normalTexture.extensions, label,
             "normalTexture", false, "its faces are shaded without it");
    p.normalScale = m.normalTexture.scale;
    double strength = extensionNumber(ctx_, m.extensions, "KHR_materials_emissive_strength",
                                      "emissiveStrength", 1, label);
    if (strength < 0) ctx_.fail(label + ": emissiveStrength must not be negative");
    p.emissive = Vec3(unit(e[0]), unit(e[1]), unit(e[2])) * strength;
    if (!(p.emissive == Vec3(0)))
        p.emissiveTexture =
            slot(m.emissiveTexture.index, m.emissiveTexture.texCoord, m.emissiveTexture.extensions,
                 label, "emissiveTexture", true, "its emissive factor is used alone");
    if (m.alphaMode == "BLEND") {
        p.alphaMode = AlphaMode::Blend;
    } else if (m.alphaMode == "MASK") {
        p.alphaMode = AlphaMode::Mask;
        p.alphaCutoff = m.alphaCutoff;
    } else if (m.alphaMode != "OPAQUE") {
        ctx_.warn(label + ": alphaMode '" + m.alphaMode + "' is not one glTF defines: opaque");
    }
    p.doubleSided = m.doubleSided;
    // Glint's own reading of a material's extras: {"glint": {"camera": false}} hides the
    // surface from camera rays (the Blender add-on's area lights, as Cycles shows them).
    if (m.extras.IsObject() && m.extras.Has("glint")) {
        const tinygltf::Value& glint = m.extras.Get("glint");
        if (glint.IsObject() && glint.Has("camera") && glint.Get("camera").IsBool())
            p.cameraVisible = glint.Get("camera").Get<bool>();
    }
    // KHR_materials_unlit: the base colour alone; the other properties (emission among them:
    // it would make a light nothing else sees) are to be ignored.
    p.unlit = m.extensions.count("KHR_materials_unlit") > 0;
    if (p.unlit) {
        p.emissive = Vec3(0);
        p.emissiveTexture = {};
    }
    if (m.occlusionTexture.index != -1)
        ctx_.warnOnce("occlusion",
                      "occlusion textures are not read: a path tracer computes the occlusion "
                      "they approximate");

    // KHR_materials_transmission, _ior and _volume.
    const bool transmissive = m.extensions.count("KHR_materials_transmission") > 0;
    p.transmission = unit(extensionNumber(ctx_, m.extensions, "KHR_materials_transmission",
                                          "transmissionFactor", 0, label));
    if (transmissive)
        p.transmissionTexture =
            extensionSlot(m.extensions.at("KHR_materials_transmission"), "transmissionTexture",
                          label, false, "its transmission factor is used alone");
    double ior = extensionNumber(ctx_, m.extensions, "KHR_materials_ior", "ior", 1.5, label);
    if (!(ior >= 1)) ior = 1.5;  // glTF allows 0 (and nothing else below 1) for "unknown"
    p.ior = ior;
    p.thickness = std::max(0.0, extensionNumber(ctx_, m.extensions, "KHR_materials_volume",
                                                "thicknessFactor", 0, label));
    p.attenuationDistance = extensionNumber(ctx_, m.extensions, "KHR_materials_volume",
                                            "attenuationDistance", INFINITY, label);
    if (!(p.attenuationDistance > 0)) p.attenuationDistance = INFINITY;
    if (auto it = m.extensions.find("KHR_materials_volume");
        it != m.extensions.end() && it->second.IsObject() && it->second.Has("attenuationColor")) {
        const tinygltf::Value& c = it->second.Get("attenuationColor");
        if (c.IsArray() && c.ArrayLen() == 3) {
            double rgb[3];
            for (int k = 0; k < 3; ++k) {
                const tinygltf::Value& x = c.Get(k);
                rgb[k] = x.IsNumber() ? unit(x.GetNumberAsDouble()) : 1;
            }
            p.attenuationColor = {rgb[0], rgb[1], rgb[2]};
        }
    }

    mapLayers(m, p, label);

    // KHR_materials_volume_scatter: the volume's extinction (KHR_materials_volume's
    // attenuation, sigma_t = -ln(colour) / distance) is part scattering, by the single-scattering
    // albedo that gives the multi-scatter albedo `multiscatterColor` (the inversion of Chiang et
    // al. 2016, "Practical and controllable subsurface scattering for production path tracing",
    // which the extension takes): a medium inside the surface, in place of the absorption alone.
    if (auto it = m.extensions.find("KHR_materials_volume_scatter");
        it != m.extensions.end() && it->second.IsObject()) {
        const tinygltf::Value& scatter = it->second;
        const char* colourKey =
            scatter.Has("multiscatterColor") ? "multiscatterColor" : "multiscatterColorFactor";
        const Vec3 multiscatter = extensionColour(scatter, colourKey, Vec3(0), 1, label);
        double g = extensionNumber(ctx_, m.extensions, "KHR_materials_volume_scatter",
                                   "scatterAnisotropy", 0, label);
        g = std::clamp(g, -0.99, 0.99);
        if (std::isfinite(p.attenuationDistance)) {
            Medium medium;
            medium.name = out.name;
            medium.g = g;
            for (int k = 0; k < 3; ++k) {
                const double c = std::clamp(p.attenuationColor[k], 1e-6, 1.0);
                const double sigmaT = -std::log(c) / p.attenuationDistance;
                const double a = multiscatter[k];
                const double r =
                    4.09712 + 4.20863 * a - std::sqrt(9.59217 + 41.6808 * a + 17.7126 * a * a);
                const double albedo = std::clamp(1 - r * r, 0.0, 1.0);
                medium.sigmaS[k] = albedo * sigmaT;
                medium.sigmaA[k] = sigmaT - medium.sigmaS[k];
            }
            out.interior = medium;
            p.attenuationDistance = INFINITY;  // the medium absorbs now, not the surface's pass
        } else {
            ctx_.warnOnce("volume-scatter",
                          label +
                              ": KHR_materials_volume_scatter without an attenuationDistance "
                              "(KHR_materials_volume) has nothing to scatter: ignored");
        }
    }

    // The flat material the Whitted integrator renders: textures other than the base colour
    // count with their mean value. Alpha blending is not folded in: the traversal already lets
    // rays through blended texels with probability 1 - alpha (Scene::intersect), for the
    // Whitted integrator as for the path tracer, and blending here too would let light through
    // twice.
    const std::shared_ptr<const TextureImage>& baseImage = p.baseColorTexture.image;
    double flatMetallic = metallic, flatRoughness = roughness;
    if (p.metallicRoughnessTexture) {
        Vec3 mean = p.metallicRoughnessTexture.image->average();
        flatRoughness *= mean.y;  // glTF: roughness in green, metalness in blue
        flatMetallic *= mean.z;
    }
    Vec3 emission = p.emissive;
    if (p.emissiveTexture) emission = emission * p.emissiveTexture.image->average();
    double opacity = 1;
    if (p.alphaMode == AlphaMode::Mask) opacity = alpha >= m.alphaCutoff ? 1 : 0;
    const double transmission = p.transmission;
    const double flatIor = transmissive ? ior : 1;

    Material& g = out.material;
    const Vec3 baseMean = baseImage ? base * baseImage->average() : base;
    g.diffuse = base * ((1 - flatMetallic) * (1 - transmission) * opacity);
    g.specular = (Vec3(kDielectricF0 * (1 - flatMetallic)) + baseMean * flatMetallic) * opacity;
    g.roughness = flatRoughness * flatRoughness;  // perceptual roughness squared is GGX's alpha
    g.shininess = kSmoothShininess;               // used only where the roughness is 0
    g.emission = emission * opacity;
    // A single-sided surface has no back (viewers cull it): it emits from its front only, as
    // an area light does. Closed emitters are unchanged; a single-sided panel lights one side.
    g.frontEmissionOnly = !p.doubleSided;
    g.transmission = base * (transmission * (1 - flatMetallic) * opacity) + Vec3(1 - opacity);
    g.ior = flatIor;
    // Ambient light as for MTL materials without Ka: a dim version of the surface's colour.
    g.ambient = (baseImage ? g.diffuse * baseImage->average() : g.diffuse) * kMtlAmbientLight;
    if (baseImage) {
        Texture t;
        t.kind = Texture::Kind::Image;
        t.wrap = p.baseColorTexture.wrapS;
        t.image = baseImage;
        t.a = g.diffuse;  // the texel times the factor, where Glint's diffuse colour goes
        out.texture = t;
    }
    return out;
}

TextureSlot Materials::slot(int index, int texCoord, const tinygltf::ExtensionMap& extensions,
                            const std::string& material, const char* slotName, bool srgb,
                            const char* instead) {
    TextureSlot out;
    if (index == -1) return out;
    const std::string user = material + " " + slotName;
    const auto& textures = ctx_.model.textures;
    if (index < 0 || static_cast<size_t>(index) >= textures.size())
        missing(ctx_, "texture", index, textures.size(), user);
    const tinygltf::Texture& texture = textures[static_cast<size_t>(index)];
    // KHR_texture_transform: offset, rotation, scale, and perhaps another coordinate set.
    if (auto it = extensions.find("KHR_texture_transform");
        it != extensions.end() && it->second.IsObject()) {
        const tinygltf::Value& x = it->second;
        auto pair = [&](const char* key, double fallback, double& a, double& b) {
            a = b = fallback;
            if (!x.Has(key)) return;
            const tinygltf::Value& v = x.Get(key);
            if (!v.IsArray() || v.ArrayLen() != 2 || !v.Get(0).IsNumber() || !v.Get(1).IsNumber())
                ctx_.fail(user + ": KHR_texture_transform " + key + " must be two numbers");
            a = v.Get(0).GetNumberAsDouble();
            b = v.Get(1).GetNumberAsDouble();
        };
        double ou, ov, su, sv;
        pair("offset", 0, ou, ov);
        pair("scale", 1, su, sv);
        double rotation = x.Has("rotation") && x.Get("rotation").IsNumber()
                              ? x.Get("rotation").GetNumberAsDouble()
                              : 0;
        if (!std::isfinite(ou) || !std::isfinite(ov) || !std::isfinite(su) || !std::isfinite(sv) ||
            !std::isfinite(rotation))
            ctx_.fail(user + ": KHR_texture_transform must have finite numbers");
        out.setTransform(ou, ov, rotation, su, sv);
        if (x.Has("texCoord") && x.Get("texCoord").IsInt()) texCoord = x.Get("texCoord").Get<int>();
    }
    if (texCoord < 0 || texCoord > 1) {
        ctx_.warn(material + ": its " + slotName + " uses TEXCOORD_" + std::to_string(texCoord) +
                  ", and Glint reads TEXCOORD_0 and TEXCOORD_1 only: " + instead);
        return {};
    }
    out.texCoord = static_cast<uint8_t>(texCoord);
    // EXT_texture_webp: its WebP image in place of `source` (a fallback, if there is one).
    int source = texture.source;
    if (auto it = texture.extensions.find("EXT_texture_webp");
        it != texture.extensions.end() && it->second.IsObject() && decodesWebp()) {
        const tinygltf::Value& webp = it->second.Get("source");
        if (webp.IsInt()) source = webp.Get<int>();
    }
    if (source == -1) {
        ctx_.warn(material + ": " + describe("texture", static_cast<size_t>(index), "") +
                  " has no image Glint reads (no 'source'): " + instead);
        return {};
    }
    const auto& images = ctx_.model.images;
    if (source < 0 || static_cast<size_t>(source) >= images.size())
        missing(ctx_, "image", source, images.size(), "texture " + std::to_string(index));
    if (texture.sampler != -1) {
        const auto& samplers = ctx_.model.samplers;
        if (texture.sampler < 0 || static_cast<size_t>(texture.sampler) >= samplers.size())
            missing(ctx_, "sampler", texture.sampler, samplers.size(),
                    "texture " + std::to_string(index));
        const tinygltf::Sampler& s = samplers[static_cast<size_t>(texture.sampler)];
        auto wrap = [](int mode) {
            return mode == TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE     ? TextureWrap::Clamp
                   : mode == TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT ? TextureWrap::MirroredRepeat
                                                                   : TextureWrap::Repeat;
        };
        out.wrapS = wrap(s.wrapS);
        out.wrapT = wrap(s.wrapT);
    }
    std::string problem;
    out.image = image(source, srgb, problem);
    if (!out.image) ctx_.warn(material + ": " + problem + "; " + instead);
    return out;
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
