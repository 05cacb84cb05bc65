#pragma once
/// The studio environment: the neutral light a bare model is shown in (`glint model.gltf`,
/// docs/cli.md "Rendering a model"), computed when first asked for, with no file to read.
///
/// An equirectangular map (scene/environment.h) of white, grey and black only:
/// - a **dome** of soft grey: the sky half brighter towards the zenith, the ground half a
///   lighter grey near the horizon, the two blended over a few degrees at the horizon;
/// - three **softboxes**, flat rectangles far away with feathered edges, as a photographer
///   lights a product: a large **key** above the camera's left, a dimmer **fill** low on the
///   right, and a long **rim** strip above and behind the model (the camera of a framed model
///   looks along -z from the +z side).
///
/// Its radiance is in the units a glTF base colour is lit by: an upward-facing white
/// Lambertian surface reflects about 1 (its irradiance over pi: 1.06; 0.86 facing the camera,
/// 0.48 facing down), so base colours show as themselves through the PBR Neutral tone mapper,
/// and the softboxes' reflections in metals and glossy paint read as highlights.

#include <memory>

#include "glint/scene/environment.h"

namespace glint {

/// Texels of the studio map: fine enough for the softboxes' edges seen in a mirror.
inline constexpr int kStudioWidth = 256, kStudioHeight = 128;

/// The radiance of the studio environment arriving from unit direction `dir`, exactly (the map
/// holds this at its texel centres).
Vec3 studioRadiance(const Vec3& dir);

/// The studio environment map, built on the first call (about 7 ms) and shared after it.
/// Thread-safe.
std::shared_ptr<const EnvironmentMap> studioEnvironment();

}  // namespace glint
