#pragma once
/// Small helpers the BSDF implementations share (bsdf.cpp, pbr_bsdf.cpp); not a public API.

#include <algorithm>
#include <cmath>

#include "glint/math/vec3.h"
#include "glint/render/bsdfs/optics.h"

namespace glint::bsdf_util {

/// `v` mirrored in the surface plane: two-sided lobes evaluate a wo below the surface as its
/// image above.
inline Vec3 flipZ(const Vec3& v) { return {v.x, v.y, -v.z}; }
inline bool sameHemisphere(const Vec3& a, const Vec3& b) { return a.z * b.z > 0; }
/// The mirror direction of wo about the normal +z.
inline Vec3 mirror(const Vec3& wo) { return {-wo.x, -wo.y, wo.z}; }

inline double mean(const Vec3& v) { return (v.x + v.y + v.z) / 3; }

/// (1 - c)^5, Schlick's weight for cosine c.
inline double schlickWeight(double c) {
    double m = std::clamp(1 - c, 0.0, 1.0);
    return (m * m) * (m * m) * m;
}

/// Schlick's Fresnel approximation for cosine `cosH` between the direction and the normal.
inline Vec3 schlick(const Vec3& f0, double cosH) {
    return f0 + (Vec3(1) - f0) * schlickWeight(cosH);
}

/// The GGX reflection BRDF D G2 F / (4 cos_o cos_i) for o, i above the surface and their unit
/// half-vector h.
inline Vec3 ggxReflection(const Ggx& ggx, const Vec3& f0, const Vec3& o, const Vec3& i,
                          const Vec3& h) {
    return schlick(f0, dot(o, h)) * (ggx.d(h) * ggx.g2(o, i) / (4 * o.z * i.z));
}

/// The density of the visible-normal sampling of reflections: D_o(h) / (4 o.h) with
/// D_o(h) = G1(o) (o.h) D(h) / cos_o (Heitz 2018, eq. 3), for o above the surface.
inline double ggxReflectionPdf(const Ggx& ggx, const Vec3& o, const Vec3& h) {
    return ggx.g1(o) * ggx.d(h) / (4 * o.z);
}

}  // namespace glint::bsdf_util
