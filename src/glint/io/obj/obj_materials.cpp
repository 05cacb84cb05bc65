// MTL materials as Glint materials, and their diffuse textures (docs/scene-format.md,
// "MTL materials").

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <numbers>

#include "glint/core/error.h"
#include "glint/io/image/texture_io.h"
#include "glint/io/obj/obj_internal.h"
#include "glint/io/obj/obj_loader.h"

namespace glint::obj {
namespace {

bool isBlank(char c) { return c == ' ' || c == '\t'; }

/// Calls `f(line, lineNumber)` for each line of `text`, split and counted as tinyobjloader's
/// reader does (LF, CR or CR LF), with leading and trailing blanks removed.
template <typename F>
void forEachLine(std::string_view text, F f) {
    size_t pos = 0;
    int number = 0;
    while (pos < text.size()) {
        size_t end = text.find_first_of("\r\n", pos);
        if (end == std::string_view::npos) end = text.size();
        std::string_view line = text.substr(pos, end - pos);
        pos = end;
        if (pos < text.size())
            pos += text[pos] == '\r' && pos + 1 < text.size() && text[pos + 1] == '\n' ? 2 : 1;
        ++number;
        while (!line.empty() && isBlank(line.front())) line.remove_prefix(1);
        while (!line.empty() && isBlank(line.back())) line.remove_suffix(1);
        f(line, number);
    }
}

/// Whether `line` starts with the keyword `key` followed by a blank.
bool statement(std::string_view line, std::string_view key) {
    return line.size() > key.size() && line.starts_with(key) && isBlank(line[key.size()]);
}

Vec3 colour(const tinyobj::real_t (&c)[3]) { return {c[0], c[1], c[2]}; }

/// A slot for an MTL texture: its image, clamping, and -o / -s as a transform.
TextureSlot mtlSlot(std::shared_ptr<const TextureImage> image,
                    const tinyobj::texture_option_t& opt) {
    TextureSlot slot;
    if (!image) return slot;
    slot.image = std::move(image);
    slot.wrapS = slot.wrapT = opt.clamp ? TextureWrap::Clamp : TextureWrap::Repeat;
    // MTL: (u, v) -> (u su + ou, v sv + ov) with v up; the slot's matrix works on t = 1 - v.
    const double su = opt.scale[0], sv = opt.scale[1], ou = opt.origin_offset[0],
                 ov = opt.origin_offset[1];
    if (std::isfinite(su) && std::isfinite(sv) && std::isfinite(ou) && std::isfinite(ov))
        slot.transform = {su, 0, ou, 0, sv, 1 - sv - ov};
    return slot;
}

/// The physically based material of an MTL entry that uses the PBR extensions: Kd (and
/// map_Kd) the base colour, Pm / map_Pm the metalness, Pr / map_Pr the roughness, Ke / map_Ke
/// the emission, norm (or map_Bump, as Blender's exporter writes normal maps) a tangent-space
/// normal map scaled by -bm, d the alpha (blended), Ni the index of refraction, and the
/// layers below.
template <typename Load>
PbrMaterial mapMtlPbr(const tinyobj::material_t& m, const Vec3& tint,
                      const std::optional<Texture>& diffuse, Load& load) {
    auto unit = [](double x) { return std::isfinite(x) ? std::clamp(x, 0.0, 1.0) : 0.0; };
    PbrMaterial p;
    p.baseColor = {unit(tint.x), unit(tint.y), unit(tint.z)};
    if (diffuse) p.baseColorTexture = mtlSlot(diffuse->image, m.diffuse_texopt);
    p.metallic = unit(m.metallic);
    p.roughness = unit(m.roughness);
    p.metallicTexture =
        mtlSlot(load(m.metallic_texname, m.metallic_texopt, false, "its Pm is used alone"),
                m.metallic_texopt);
    p.roughnessTexture =
        mtlSlot(load(m.roughness_texname, m.roughness_texopt, false, "its Pr is used alone"),
                m.roughness_texopt);
    const bool norm = !m.normal_texname.empty();
    const std::string& normalName = norm ? m.normal_texname : m.bump_texname;
    const tinyobj::texture_option_t& normalOpt = norm ? m.normal_texopt : m.bump_texopt;
    p.normalTexture =
        mtlSlot(load(normalName, normalOpt, false, "its faces are shaded without it"), normalOpt);
    p.normalScale = std::isfinite(normalOpt.bump_multiplier) ? normalOpt.bump_multiplier : 1;
    const Vec3 ke(m.emission[0], m.emission[1], m.emission[2]);
    p.emissive = Vec3(std::max(0.0, ke.x), std::max(0.0, ke.y), std::max(0.0, ke.z));
    p.emissiveTexture =
        mtlSlot(load(m.emissive_texname, m.emissive_texopt, true, "its Ke is used alone"),
                m.emissive_texopt);
    if (!m.emissive_texname.empty() && p.emissive == Vec3(0)) p.emissive = Vec3(1);
    if (m.dissolve < 1) {
        p.alphaMode = AlphaMode::Blend;
        p.alpha = unit(m.dissolve);
    }
    if (m.ior >= 1) p.ior = m.ior;
    p.doubleSided = true;  // OBJ has no notion of sidedness: both faces are surfaces
    // The layers: Pc / Pcr a clearcoat and its roughness, Ps (and map_Ps) a white sheen of
    // that strength (roughness 0.5: MTL has none), aniso / anisor the anisotropy and its
    // rotation (turns, as Blender writes it).
    p.clearcoat = unit(m.clearcoat_thickness);
    p.clearcoatRoughness = unit(m.clearcoat_roughness);
    p.sheenColor = Vec3(unit(m.sheen));
    p.sheenRoughness = 0.5;
    p.sheenColorTexture = mtlSlot(
        load(m.sheen_texname, m.sheen_texopt, true, "its Ps is used alone"), m.sheen_texopt);
    if (p.sheenColorTexture && p.sheenColor == Vec3(0)) p.sheenColor = Vec3(1);
    p.anisotropy = unit(m.anisotropy);
    p.anisotropyRotation =
        std::isfinite(m.anisotropy_rotation) ? m.anisotropy_rotation * 2 * std::numbers::pi : 0;
    return p;
}

}  // namespace

std::vector<MtlEntry> scanMtl(std::string_view text) {
    std::vector<MtlEntry> entries;
    MtlEntry current;  // LoadMtl's unnamed first material, kept only if nothing follows
    forEachLine(text, [&](std::string_view line, int number) {
        if (statement(line, "newmtl")) {
            if (current.line > 0) entries.push_back(current);
            current = MtlEntry{number};
        } else if (statement(line, "Ka")) {
            current.hasKa = true;
        } else if (statement(line, "Kd")) {
            current.hasKd = true;
        } else if (statement(line, "illum")) {
            current.hasIllum = true;
        } else if (statement(line, "Pr") || statement(line, "Pm") || statement(line, "Ps") ||
                   statement(line, "map_Pr") || statement(line, "map_Pm") ||
                   statement(line, "map_Ps") || statement(line, "norm") ||
                   statement(line, "aniso") || statement(line, "Pc") || statement(line, "Pcr")) {
            current.pbr = true;
        }
    });
    entries.push_back(current);
    return entries;
}

MeshMaterial mapMtlMaterial(const tinyobj::material_t& m, const MtlEntry& entry,
                            const MtlSource& source, TextureCache& cache,
                            std::vector<Diagnostic>& warnings, const LoadLimits& limits) {
    const FileLoc at{source.file, entry.line, entry.line > 0 ? 1 : 0};
    const std::string quotedName = "'" + m.name + "'";
    Vec3 ka = colour(m.ambient), kd = colour(m.diffuse), ks = colour(m.specular);
    Vec3 ke = colour(m.emission);
    double ns = m.shininess, ni = m.ior, d = m.dissolve;
    if (!isFinite(ka) || !isFinite(kd) || !isFinite(ks) || !isFinite(ke) || !std::isfinite(ns) ||
        !std::isfinite(ni) || !std::isfinite(d))
        throw SceneError(at, "material " + quotedName + " has a value that is not a finite number");

    MeshMaterial out;
    out.name = m.name;
    Material& g = out.material;
    // The colour a diffuse texture is multiplied by (Kd, as MTL has it), and the colour used
    // where there is no texture: Kd, or tinyobjloader's grey when only map_Kd is given.
    Vec3 tint = entry.hasKd ? kd : Vec3(1);
    g.diffuse = kd;
    // A texture of the material by its MTL name and options, through the cache; null (with a
    // warning) if it cannot be read.
    auto load = [&](const std::string& texname, const tinyobj::texture_option_t& opt, bool srgb,
                    const char* instead) -> std::shared_ptr<const TextureImage> {
        if (texname.empty()) return nullptr;
        std::string name = texname;
        std::replace(name.begin(), name.end(), '\\', '/');  // paths from Windows exporters
        std::string path = name.front() == '/' || source.textureDir.empty()
                               ? name
                               : source.textureDir + "/" + name;
        srgb = srgb && opt.colorspace != "linear";
        std::string key = path + (srgb ? "" : "\n(linear)");
        if (auto it = cache.find(key); it != cache.end()) return it->second;
        std::shared_ptr<const TextureImage> image;
        if (source.readTextures) {
            try {
                image = loadTextureImage(path, srgb, limits);
            } catch (const RenderError& e) {
                warnings.push_back(
                    {at, "material " + quotedName + ": " + e.what() + "; " + instead});
            }
            cache[key] = image;
        }
        return image;
    };
    if (auto image = load(m.diffuse_texname, m.diffuse_texopt, true,
                          "its faces show its diffuse colour instead")) {
        Texture t;
        t.kind = Texture::Kind::Image;
        t.wrap = m.diffuse_texopt.clamp ? TextureWrap::Clamp : TextureWrap::Repeat;
        t.image = image;
        t.a = tint;
        out.texture = t;
    }
    // Ambient: Ka under OpenGL's default ambient light, or the diffuse colour (the texture's
    // mean for textured materials) when there is no Ka: never the course's flat 0.2 grey.
    Vec3 meanDiffuse = out.texture ? tint * out.texture->image->average() : g.diffuse;
    g.ambient = (entry.hasKa ? ka : meanDiffuse) * kMtlAmbientLight;
    // illum 0 and 1 are MTL's models without highlights; Glint's specular is also its mirror.
    bool noSpecular = entry.hasIllum && (m.illum == 0 || m.illum == 1);
    g.specular = noSpecular ? Vec3(0) : ks;
    if (ns < 0) {
        warnings.push_back(
            {at, "material " + quotedName + " has a negative Ns (shininess); using 0"});
        ns = 0;
    }
    g.shininess = ns;
    g.emission = ke;
    // A physically based entry blends by d in the traversal (AlphaMode::Blend, for every
    // integrator): its flat material stays opaque, or light would pass twice.
    if (d < 1 && !entry.pbr) {
        // Dissolve as a dielectric: what is not opaque is transmitted (refracted by Ni; with
        // Ni 1, the default, it passes straight through), and the opaque part is diffuse.
        d = std::max(d, 0.0);
        g.transmission = Vec3(1 - d);
        g.diffuse = g.diffuse * d;
        g.ambient = g.ambient * d;
        if (out.texture) out.texture->a = out.texture->a * d;
        if (ni > 0) {
            g.ior = ni;
        } else {
            char value[32];
            std::snprintf(value, sizeof value, "%g", ni);
            warnings.push_back({at, "material " + quotedName + " has Ni " + value +
                                        ", not an index of refraction; using 1"});
            g.ior = 1;
        }
    }
    if (entry.pbr) out.pbr = mapMtlPbr(m, tint, out.texture, load);
    return out;
}

std::vector<Diagnostic> libraryWarnings(std::string_view text, const std::string& file) {
    std::vector<Diagnostic> out;
    for (size_t pos = 0; pos < text.size();) {
        size_t end = std::min(text.find('\n', pos), text.size());
        std::string_view line = text.substr(pos, end - pos);
        pos = end + 1;
        Diagnostic d;
        d.loc.file = file;
        // "... (line 12.)" or "... (line 12 in .mtl.)": the line, and the message without it.
        if (size_t at = line.rfind(" (line ");
            at != std::string_view::npos && line.ends_with(")")) {
            d.loc.line = std::atoi(std::string(line.substr(at + 7)).c_str());
            d.loc.column = d.loc.line > 0 ? 1 : 0;
            line = line.substr(0, at);
        }
        while (!line.empty() && (line.back() == '.' || isBlank(line.back()) || line.back() == '\r'))
            line.remove_suffix(1);
        if (line.empty()) continue;
        constexpr std::string_view kBoth = "Both `d` and `Tr` parameters defined for \"";
        if (line.starts_with(kBoth) && line.find('"', kBoth.size()) != std::string_view::npos) {
            std::string_view name = line.substr(kBoth.size());
            name = name.substr(0, name.find('"'));
            d.message = "material '" + std::string(name) + "' has both d and Tr: d is used";
        } else {
            d.message = "tinyobjloader: " + std::string(line);
        }
        out.push_back(std::move(d));
    }
    return out;
}

FileLoc statementAt(std::string_view text, size_t offset, const std::string& file, int token) {
    offset = std::min(offset, text.size());
    // The statement's last byte is at offset - 1: step back over its line end, then to the
    // start of the line.
    size_t end = offset;
    if (end > 0 && text[end - 1] == '\n') --end;
    if (end > 0 && text[end - 1] == '\r') --end;
    size_t start = end;
    while (start > 0 && text[start - 1] != '\n' && text[start - 1] != '\r') --start;
    int line = 1;
    for (size_t i = 0; i < start; ++i)
        if (text[i] == '\n' || (text[i] == '\r' && (i + 1 >= start || text[i + 1] != '\n'))) ++line;
    // Column of the token numbered `token`.
    size_t i = start;
    for (int k = 0;; ++k) {
        while (i < end && isBlank(text[i])) ++i;
        if (k == token || i >= end) break;
        while (i < end && !isBlank(text[i])) ++i;
    }
    return {file, line, static_cast<int>(i - start) + 1};
}

}  // namespace glint::obj
