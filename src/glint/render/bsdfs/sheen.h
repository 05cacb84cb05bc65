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

/// The directional albedo E(mu) of sheenLobe() for a viewer at cos theta = mu, from the table
/// below (bilinear between its entries).
double sheenAlbedo(double alpha, double mu);

/// sheenAlbedo() by direct quadrature, the table's reference (tests, and the tool that writes
/// the table).
double sheenAlbedoByQuadrature(double alpha, double mu, int steps);

/// The table of sheenAlbedo(): rows uniform in the perceptual roughness sqrt(alpha) from
/// sqrt(kMinSheenAlpha) to 1, columns uniform in sqrt(mu) (smooth sheens reflect only near
/// grazing angles, where their albedo changes fastest with both). Each entry is
/// sheenAlbedoByQuadrature(rowAlpha(r), columnMu(c), kSteps) rounded to float, written into
/// sheen_albedo_table.cpp by tools/sheen_albedo_table.cpp (it took 0.5 s at every start when it
/// was computed at run time); the unit tests recompute every entry.
namespace sheen_albedo_table {
constexpr int kRows = 24, kColumns = 32, kSteps = 48;
double rowAlpha(int r);
double columnMu(int c);
extern const float kE[kRows * kColumns];
}  // namespace sheen_albedo_table

}  // namespace glint
