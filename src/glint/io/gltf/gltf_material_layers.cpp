// The glTF material extensions that layer over the metallic-roughness base (render/bsdfs/bsdf.h's
// MetallicRoughness): KHR_materials_clearcoat, _sheen, _specular, _anisotropy, _iridescence and
// _diffuse_transmission (and _dispersion), read into the PbrMaterial with their factors and
// textures.

#include <algorithm>
#include <cmath>

#include "glint/io/gltf/gltf_internal.h"

namespace glint::gltf {
namespace {

/// The extension object `name` of `m`, or null.
const tinygltf::Value* extensionOf(const tinygltf::Material& m, const char* name) {
    auto it = m.extensions.find(name);
    return it != m.extensions.end() && it->second.IsObject() ? &it->second : nullptr;
}

}  // namespace

TextureSlot Materials::extensionSlot(const tinygltf::Value& ext, const char* key,
                                     const std::string& material, bool srgb, const char* instead) {
    if (!ext.IsObject() || !ext.Has(key)) return {};
    const tinygltf::Value& t = ext.Get(key);
    auto integer = [&](const char* k, int fallback) {
        return t.IsObject() && t.Has(k) && t.Get(k).IsInt() ? t.Get(k).Get<int>() : fallback;
    };
    tinygltf::ExtensionMap own;
    if (t.IsObject() && t.Has("extensions") && t.Get("extensions").IsObject())
        for (const std::string& k : t.Get("extensions").Keys()) own[k] = t.Get("extensions").Get(k);
    return slot(integer("index", -1), integer("texCoord", 0), own, material, key, srgb, instead);
}

Vec3 Materials::extensionColour(const tinygltf::Value& ext, const char* key, Vec3 fallback,
                                double most, const std::string& label) const {
    if (!ext.Has(key)) return fallback;
    const tinygltf::Value& c = ext.Get(key);
    if (!c.IsArray() || c.ArrayLen() != 3) ctx_.fail(label + ": " + key + " must be three numbers");
    double rgb[3];
    for (int k = 0; k < 3; ++k) {
        const tinygltf::Value& x = c.Get(k);
        rgb[k] = x.IsNumber() ? x.GetNumberAsDouble() : NAN;
        if (!std::isfinite(rgb[k])) ctx_.fail(label + ": " + key + " must be finite numbers");
        rgb[k] = std::clamp(rgb[k], 0.0, most);
    }
    return Vec3(rgb[0], rgb[1], rgb[2]);
}

void Materials::mapLayers(const tinygltf::Material& m, PbrMaterial& p, const std::string& label) {
    auto number = [&](const char* extension, const char* key, double fallback) {
        return extensionNumber(ctx_, m.extensions, extension, key, fallback, label);
    };
    auto unitNumber = [&](const char* extension, const char* key, double fallback) {
        return std::clamp(number(extension, key, fallback), 0.0, 1.0);
    };
    // A colour of three numbers, each at least 0 (and at most `most`).
    auto colour = [&](const tinygltf::Value& ext, const char* key, Vec3 fallback, double most) {
        return extensionColour(ext, key, fallback, most, label);
    };

    if (const tinygltf::Value* x = extensionOf(m, "KHR_materials_clearcoat")) {
        const char* name = "KHR_materials_clearcoat";
        p.clearcoat = unitNumber(name, "clearcoatFactor", 0);
        p.clearcoatRoughness = unitNumber(name, "clearcoatRoughnessFactor", 0);
        p.clearcoatTexture = extensionSlot(*x, "clearcoatTexture", label, false,
                                           "its clearcoat factor is used alone");
        p.clearcoatRoughnessTexture = extensionSlot(*x, "clearcoatRoughnessTexture", label, false,
                                                    "its clearcoat roughness factor is used alone");
        p.clearcoatNormalTexture = extensionSlot(*x, "clearcoatNormalTexture", label, false,
                                                 "its coat follows the surface's normal");
        if (x->Has("clearcoatNormalTexture") && x->Get("clearcoatNormalTexture").IsObject() &&
            x->Get("clearcoatNormalTexture").Has("scale")) {
            const tinygltf::Value& s = x->Get("clearcoatNormalTexture").Get("scale");
            p.clearcoatNormalScale = s.IsNumber() ? s.GetNumberAsDouble() : NAN;
            if (!std::isfinite(p.clearcoatNormalScale))
                ctx_.fail(label + ": clearcoatNormalTexture's scale must be a finite number");
        }
    }
    if (const tinygltf::Value* x = extensionOf(m, "KHR_materials_sheen")) {
        const char* name = "KHR_materials_sheen";
        p.sheenColor = colour(*x, "sheenColorFactor", Vec3(0), 1);
        p.sheenRoughness = unitNumber(name, "sheenRoughnessFactor", 0);
        p.sheenColorTexture = extensionSlot(*x, "sheenColorTexture", label, true,
                                            "its sheen colour factor is used alone");
        p.sheenRoughnessTexture = extensionSlot(*x, "sheenRoughnessTexture", label, false,
                                                "its sheen roughness factor is used alone");
    }
    if (const tinygltf::Value* x = extensionOf(m, "KHR_materials_specular")) {
        const char* name = "KHR_materials_specular";
        p.specular = unitNumber(name, "specularFactor", 1);
        // The colour may exceed 1 (f0 is clamped after the product with the index's f0).
        p.specularColor = colour(*x, "specularColorFactor", Vec3(1), INFINITY);
        p.specularTexture =
            extensionSlot(*x, "specularTexture", label, false, "its specular factor is used alone");
        p.specularColorTexture = extensionSlot(*x, "specularColorTexture", label, true,
                                               "its specular colour factor is used alone");
    }
    if (const tinygltf::Value* x = extensionOf(m, "KHR_materials_anisotropy")) {
        const char* name = "KHR_materials_anisotropy";
        p.anisotropy = unitNumber(name, "anisotropyStrength", 0);
        p.anisotropyRotation = number(name, "anisotropyRotation", 0);
        p.anisotropyTexture = extensionSlot(*x, "anisotropyTexture", label, false,
                                            "its anisotropy runs along the tangent");
    }
    if (const tinygltf::Value* x = extensionOf(m, "KHR_materials_iridescence")) {
        const char* name = "KHR_materials_iridescence";
        p.iridescence = unitNumber(name, "iridescenceFactor", 0);
        p.iridescenceIor = std::max(1.0, number(name, "iridescenceIor", 1.3));
        p.iridescenceThicknessMin = std::max(0.0, number(name, "iridescenceThicknessMinimum", 100));
        p.iridescenceThicknessMax = std::max(0.0, number(name, "iridescenceThicknessMaximum", 400));
        p.iridescenceTexture = extensionSlot(*x, "iridescenceTexture", label, false,
                                             "its iridescence factor is used alone");
        p.iridescenceThicknessTexture =
            extensionSlot(*x, "iridescenceThicknessTexture", label, false,
                          "its film has the maximum thickness everywhere");
    }
    p.dispersion = std::max(0.0, number("KHR_materials_dispersion", "dispersion", 0));
    if (const tinygltf::Value* x = extensionOf(m, "KHR_materials_diffuse_transmission")) {
        const char* name = "KHR_materials_diffuse_transmission";
        p.diffuseTransmission = unitNumber(name, "diffuseTransmissionFactor", 0);
        p.diffuseTransmissionColor = colour(*x, "diffuseTransmissionColorFactor", Vec3(1), 1);
        p.diffuseTransmissionTexture = extensionSlot(*x, "diffuseTransmissionTexture", label, false,
                                                     "its factor is used alone");
        p.diffuseTransmissionColorTexture = extensionSlot(
            *x, "diffuseTransmissionColorTexture", label, true, "its colour factor is used alone");
    }
}

}  // namespace glint::gltf
