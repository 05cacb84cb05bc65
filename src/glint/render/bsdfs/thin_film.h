#pragma once
/// Thin-film interference (KHR_materials_iridescence): the reflectance of a film of index
/// `filmIor` and thickness `thickness` (nanometres) on a base, seen from air, after Belcour and
/// Barla, "A Practical Extension to Microfacet Theory for the Modeling of Varying Iridescence"
/// (SIGGRAPH 2017), as the extension's specification writes it: the Airy sum of the film's
/// two interfaces (Schlick reflectances, the phase shifts of a denser or lighter medium) up to
/// the second order, integrated against the CIE colour matching functions in Fourier space
/// (their Gaussian fits; the numbers are the paper's) and turned into linear Rec. 709 RGB.

#include "glint/math/vec3.h"

namespace glint {

/// The film's reflectance at cosine `cosTheta` between the view and the micro-normal, over a
/// base of normal-incidence reflectance `baseF0` (a dielectric's ((n - 1) / (n + 1))^2, or a
/// metal's base colour). Each channel in [0, 1]; thickness 0 gives the base's reflectance.
Vec3 thinFilmReflectance(double cosTheta, double filmIor, double thickness, const Vec3& baseF0);

}  // namespace glint
