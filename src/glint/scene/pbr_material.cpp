#include "glint/scene/pbr_material.h"

#include <algorithm>
#include <cmath>

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

/// The shading normal of `si` bent by the normal map of `m` (front side).
Vec3 mappedNormal(const PbrMaterial& m, const SurfaceInteraction& si) {
    const Vec3 n = si.n;
    if (!m.normalTexture) return n;
    Rgba t = m.normalTexture.sample(si, {Vec3(0.5, 0.5, 1), 1});
    Vec3 tangent;
    double sign = 1;
    if (si.hasTangent) {
        tangent = si.tangent;
        sign = si.tangentSign;
    } else {
        tangent = si.dpdu;
    }
    // Gram-Schmidt against the interpolated normal; without a tangent the map cannot apply.
    tangent = tangent - n * dot(n, tangent);
    double len = length(tangent);
    if (!(len > 1e-12) || !std::isfinite(len)) return n;
    tangent = tangent / len;
    const Vec3 bitangent = cross(n, tangent) * sign;
    const double x = (2 * t.rgb.x - 1) * m.normalScale, y = (2 * t.rgb.y - 1) * m.normalScale;
    const double z = 2 * t.rgb.z - 1;
    Vec3 mapped = tangent * x + bitangent * y + n * z;
    double ml = length(mapped);
    if (!(ml > 1e-12) || !std::isfinite(ml)) return n;
    return mapped / ml;
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
    s.normal = mappedNormal(m, si);
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
