#pragma once
/// The sheen of cloth and velvet (KHR_materials_sheen): the "Charlie" microfacet lobe of
/// Estevez and Kulla, "Production Friendly Microfacet Sheen BRDF" (Sony Pictures Imageworks,
/// 2017), as the extension's specification uses it, with alpha the sheen roughness squared:
///     D(h) = (2 + 1 / alpha) sin(theta_h)^(1 / alpha) / (2 pi)
///     V    = 1 / ((1 + Lambda(cos_o) + Lambda(cos_i)) 4 cos_o cos_i)
///     f    = sheenColor D(h) V
/// Lambda is the paper's fitted curve (its five coefficients at alpha 0 and 1, blended by
/// (1 - alpha)^2; the numbers are the paper's). The layer beneath is scaled by
///     min(1 - max(sheenColor) E(cos_o), 1 - max(sheenColor) E(cos_i)),
/// E(mu) the directional albedo of f with a white colour, from sheenAlbedo(): so the sheen
/// takes from the base what it reflects, as the specification writes it. Sampled
/// cosine-weighted (the lobe is broad, brightest towards grazing angles).

#include "glint/math/vec3.h"

namespace glint {

/// Sheen roughness alpha below this is raised to it (a perceptual roughness of 0.07): below,
/// the lobe shrinks to a sliver at grazing angles that no sampling finds.
constexpr double kMinSheenAlpha = 0.0049;

/// D V of the Charlie lobe (white) for o, i above the surface (z > 0), in 1 / sr.
double sheenLobe(double alpha, const Vec3& o, const Vec3& i);

/// The directional albedo E(mu) of sheenLobe() for a viewer at cos theta = mu, from a table
/// over alpha and mu computed once by quadrature (bilinear between its entries).
double sheenAlbedo(double alpha, double mu);

/// sheenAlbedo() by direct quadrature, the table's own reference (tests).
double sheenAlbedoByQuadrature(double alpha, double mu, int steps);

}  // namespace glint
