#pragma once
/// The optics of Glint's extended materials: Snell refraction, exact dielectric Fresnel
/// reflectance, and the GGX (Trowbridge-Reitz) microfacet lobe with Smith masking, sampled
/// through its distribution of visible normals.

#include <algorithm>
#include <cmath>
#include <numbers>

#include "glint/math/sampling.h"
#include "glint/math/vec3.h"

namespace glint {

/// Refracts the unit direction `d` at a surface with unit normal `n` facing the side `d`
/// comes from (dot(d, n) < 0), where `eta` = n_incident / n_transmitted. Returns false on
/// total internal reflection; otherwise sets `t` (unit length).
inline bool refract(const Vec3& d, const Vec3& n, double eta, Vec3& t) {
    double cosI = -dot(d, n);
    double sin2T = eta * eta * std::max(0.0, 1 - cosI * cosI);
    if (sin2T >= 1) return false;
    double cosT = std::sqrt(1 - sin2T);
    t = normalize(d * eta + n * (eta * cosI - cosT));
    return true;
}

/// Fresnel reflectance of unpolarised light at a smooth dielectric boundary (the exact
/// equations, not Schlick's approximation): `cosI` is the cosine of the angle of incidence,
/// `eta` = n_incident / n_transmitted. 1 under total internal reflection.
inline double fresnelDielectric(double cosI, double eta) {
    cosI = std::clamp(cosI, 0.0, 1.0);
    double sin2T = eta * eta * (1 - cosI * cosI);
    if (sin2T >= 1) return 1;
    double cosT = std::sqrt(1 - sin2T);
    double rs = (eta * cosI - cosT) / (eta * cosI + cosT);
    double rp = (cosI - eta * cosT) / (cosI + eta * cosT);
    return 0.5 * (rs * rs + rp * rp);
}

/// GGX with roughness alpha, in a local frame where the normal is +z: isotropic, or
/// anisotropic with roughness alpha along x and alphaY along y (KHR_materials_anisotropy; the
/// frame's x is then the direction of anisotropy). The isotropic formulas are kept as they are
/// (the course's images depend on them to the last bit); the anisotropic ones reduce to them.
struct Ggx {
    double alpha;
    double alphaY = -1;  ///< Roughness along y; negative: alpha (isotropic).

    bool anisotropic() const { return alphaY >= 0 && alphaY != alpha; }

    /// Microfacet distribution D(h) for a unit half-vector h (local).
    double d(const Vec3& h) const {
        if (h.z <= 0) return 0;
        if (anisotropic()) {
            double x = h.x / alpha, y = h.y / alphaY;
            double k = x * x + y * y + h.z * h.z;
            return 1 / (std::numbers::pi * alpha * alphaY * k * k);
        }
        double a2 = alpha * alpha;
        double k = h.z * h.z * (a2 - 1) + 1;
        return a2 / (std::numbers::pi * k * k);
    }
    /// Smith masking G1(v) for a unit direction v (local).
    double g1(const Vec3& v) const {
        if (v.z <= 0) return 0;
        if (anisotropic()) {
            double x = alpha * v.x, y = alphaY * v.y;
            return 2 * v.z / (v.z + std::sqrt(x * x + y * y + v.z * v.z));
        }
        double a2 = alpha * alpha;
        return 2 * v.z / (v.z + std::sqrt(a2 + (1 - a2) * v.z * v.z));
    }
    /// Separable Smith masking-shadowing G2 = G1(wo) G1(wi).
    double g2(const Vec3& wo, const Vec3& wi) const { return g1(wo) * g1(wi); }

    /// A microfacet normal drawn from the normals visible from `wo` (local, wo.z > 0), by
    /// Heitz, "Sampling the GGX Distribution of Visible Normals" (JCGT 2018). Reflecting wo
    /// about it gives wi with estimator weight f cos / pdf = F * G1(wi).
    Vec3 sampleVisibleNormal(const Vec3& wo, double u1, double u2) const {
        auto [p1, p2] = sampleUniformDisk(u1, u2);
        return visibleNormal(wo, p1, p2);
    }
    /// The visible normal that sampleVisibleNormal() reaches from the point (p1, p2) of the
    /// unit disk: uniform points of the disk give normals with the density of the visible
    /// normals, so an integral over them is an integral over the disk (ggx_albedo_table.h).
    /// p1 runs across the plane of wo and the normal: mirroring it mirrors the normal in that
    /// plane.
    Vec3 visibleNormal(const Vec3& wo, double p1, double p2raw) const {
        const double ay = alphaY >= 0 ? alphaY : alpha;
        Vec3 vh = normalize(Vec3(alpha * wo.x, ay * wo.y, wo.z));
        double len2 = vh.x * vh.x + vh.y * vh.y;
        Vec3 t1 = len2 > 0 ? Vec3(-vh.y, vh.x, 0) / std::sqrt(len2) : Vec3(1, 0, 0);
        Vec3 t2 = cross(vh, t1);
        double s = 0.5 * (1 + vh.z);
        double p2 = (1 - s) * std::sqrt(std::max(0.0, 1 - p1 * p1)) + s * p2raw;
        Vec3 nh = t1 * p1 + t2 * p2 + vh * std::sqrt(std::max(0.0, 1 - p1 * p1 - p2 * p2));
        return normalize(Vec3(alpha * nh.x, ay * nh.y, std::max(1e-12, nh.z)));
    }
};

}  // namespace glint
