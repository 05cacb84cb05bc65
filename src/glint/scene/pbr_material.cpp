#include "glint/scene/pbr_material.h"

#include <algorithm>
#include <cmath>
#include <optional>

namespace glint {

void TextureSlot::setTransform(double offsetU, double offsetV, double rotation, double scaleU,
                               double scaleV) {
    // KHR_texture_transform: T * R * S with R = [cos sin; -sin cos] (its rotation turns the
    // coordinates counter-clockwise in the image, whose v runs down).
    const double c = std::cos(rotation), s = std::sin(rotation);
    transform = {c * scaleU, s * scaleV, offsetU, -s * scaleU, c * scaleV, offsetV};
}

Rgba TextureSlot::sample(const SurfaceInteraction& si, Rgba fallback) const {
    if (!image || image->width <= 0 || image->height <= 0) return fallback;
    double u, v;
    if (texCoord == 0) {
        if (!si.hasUv) return fallback;
        u = si.u;
        v = si.v;
    } else {
        if (!si.hasUv1) return fallback;
        u = si.u1;
        v = si.v1;
    }
    if (transform != std::array<double, 6>{1, 0, 0, 0, 1, 0}) {
        const double tv = 1 - v;  // glTF's coordinates: v down the image
        const double s = transform[0] * u + transform[1] * tv + transform[2];
        const double t = transform[3] * u + transform[4] * tv + transform[5];
        u = s;
        v = 1 - t;
    }
    return sampleBilinearRgba(*image, u, v, wrapS, wrapT);
}

namespace {

double unit(double x) { return std::clamp(x, 0.0, 1.0); }

/// The tangent and bitangent of `si` (its tangents, or dp/du without them), perpendicular to
/// the interpolated normal; none where they are degenerate.
struct TangentFrame {
    Vec3 tangent, bitangent;
};
std::optional<TangentFrame> tangentFrame(const SurfaceInteraction& si) {
    const Vec3 n = si.n;
    Vec3 tangent = si.hasTangent ? si.tangent : si.dpdu;
    const double sign = si.hasTangent ? si.tangentSign : 1;
    // Gram-Schmidt against the interpolated normal.
    tangent = tangent - n * dot(n, tangent);
    double len = length(tangent);
    if (!(len > 1e-12) || !std::isfinite(len)) return std::nullopt;
    tangent = tangent / len;
    return TangentFrame{tangent, cross(n, tangent) * sign};
}

/// The interpolated normal of `si` bent by the normal map `map` of scale `scale`.
Vec3 mappedNormal(const TextureSlot& map, double scale, const SurfaceInteraction& si) {
    const Vec3 n = si.n;
    if (!map) return n;
    Rgba t = map.sample(si, {Vec3(0.5, 0.5, 1), 1});
    std::optional<TangentFrame> tf = tangentFrame(si);
    if (!tf) return n;  // without a tangent the map cannot apply
    const double x = (2 * t.rgb.x - 1) * scale, y = (2 * t.rgb.y - 1) * scale;
    const double z = 2 * t.rgb.z - 1;
    Vec3 mapped = tf->tangent * x + tf->bitangent * y + n * z;
    double ml = length(mapped);
    if (!(ml > 1e-12) || !std::isfinite(ml)) return n;
    return mapped / ml;
}

/// `value` times the channel `channel` (0 to 3, 3 alpha) of `slot` at `si`, clamped to [0, 1].
double scaled(double value, const TextureSlot& slot, int channel, const SurfaceInteraction& si) {
    if (slot) {
        const Rgba t = slot.sample(si);
        value *= channel == 3 ? t.a : t.rgb[channel];
    }
    return unit(value);
}
Vec3 scaled(const Vec3& value, const TextureSlot& slot, const SurfaceInteraction& si) {
    const Vec3 v = slot ? value * slot.sample(si).rgb : value;
    return {unit(v.x), unit(v.y), unit(v.z)};
}

/// The layers of the extensions (clearcoat, sheen, specular, anisotropy, iridescence,
/// diffuse transmission) at `si`.
void evalLayers(const PbrMaterial& m, const SurfaceInteraction& si, PbrSurface& s) {
    s.specular = scaled(m.specular, m.specularTexture, 3, si);
    s.specularColor = m.specularColor;  // may exceed 1: f0 is clamped after the product
    if (m.specularColorTexture)
        s.specularColor = s.specularColor * m.specularColorTexture.sample(si).rgb;
    s.clearcoat = scaled(m.clearcoat, m.clearcoatTexture, 0, si);
    s.clearcoatNormal = si.n;
    if (s.clearcoat > 0) {
        s.clearcoatRoughness = scaled(m.clearcoatRoughness, m.clearcoatRoughnessTexture, 1, si);
        s.clearcoatNormal = mappedNormal(m.clearcoatNormalTexture, m.clearcoatNormalScale, si);
    }
    s.sheenColor = scaled(m.sheenColor, m.sheenColorTexture, si);
    s.sheenRoughness = scaled(m.sheenRoughness, m.sheenRoughnessTexture, 3, si);
    s.diffuseTransmission = scaled(m.diffuseTransmission, m.diffuseTransmissionTexture, 3, si);
    s.diffuseTransmissionColor =
        scaled(m.diffuseTransmissionColor, m.diffuseTransmissionColorTexture, si);
    s.iridescence = scaled(m.iridescence, m.iridescenceTexture, 0, si);
    if (s.iridescence > 0) {
        s.iridescenceThickness = m.iridescenceThicknessMax;
        if (m.iridescenceThicknessTexture)
            s.iridescenceThickness = m.iridescenceThicknessMin +
                                     (m.iridescenceThicknessMax - m.iridescenceThicknessMin) *
                                         m.iridescenceThicknessTexture.sample(si).rgb.y;
    }
    if (m.anisotropy > 0) {
        std::optional<TangentFrame> tf = tangentFrame(si);
        if (!tf) return;  // no direction to stretch along
        double dx = 1, dy = 0, strength = m.anisotropy;
        if (m.anisotropyTexture) {
            const Rgba t = m.anisotropyTexture.sample(si, {Vec3(1, 0.5, 1), 1});
            dx = 2 * t.rgb.x - 1;
            dy = 2 * t.rgb.y - 1;
            strength *= t.rgb.z;
        }
        const double c = std::cos(m.anisotropyRotation), sn = std::sin(m.anisotropyRotation);
        const Vec3 dir = tf->tangent * (c * dx - sn * dy) + tf->bitangent * (sn * dx + c * dy);
        const double len = length(dir);
        if (!(len > 1e-12)) return;
        s.anisotropy = unit(strength);
        s.anisotropyDirection = dir / len;
    }
}

}  // namespace

PbrSurface evalSurface(const PbrMaterial& m, const SurfaceInteraction& si) {
    PbrSurface s;
    Vec3 base = m.baseColor;
    if (m.baseColorTexture) base = base * m.baseColorTexture.sample(si).rgb;
    if (si.hasColor) base = base * si.color;
    s.baseColor = {unit(base.x), unit(base.y), unit(base.z)};
    double metallic = m.metallic, roughness = m.roughness;
    if (m.metallicRoughnessTexture) {
        Vec3 mr = m.metallicRoughnessTexture.sample(si).rgb;
        roughness *= mr.y;
        metallic *= mr.z;
    }
    if (m.roughnessTexture) roughness *= m.roughnessTexture.sample(si).rgb.x;
    if (m.metallicTexture) metallic *= m.metallicTexture.sample(si).rgb.x;
    s.metallic = unit(metallic);
    s.roughness = unit(roughness);
    double transmission = m.transmission;
    if (m.transmissionTexture) transmission *= m.transmissionTexture.sample(si).rgb.x;
    s.transmission = unit(transmission);
    s.emission = emissionAt(m, si);
    s.normal = mappedNormal(m.normalTexture, m.normalScale, si);
    evalLayers(m, si, s);
    return s;
}

double opacityAt(const PbrMaterial& m, const SurfaceInteraction& si) {
    double a = m.alpha;
    if (m.baseColorTexture) a *= m.baseColorTexture.sample(si).a;
    if (si.hasColor) a *= si.colorAlpha;
    return unit(a);
}

Vec3 emissionAt(const PbrMaterial& m, const SurfaceInteraction& si) {
    if (m.emissive == Vec3(0)) return Vec3(0);
    if (!m.emissiveTexture) return m.emissive;
    return m.emissive * m.emissiveTexture.sample(si).rgb;
}

}  // namespace glint
