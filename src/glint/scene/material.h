#pragma once
/// The course's material: OpenGL-style terms plus the mirror weight (= specular), and Glint's
/// extensions: transmission with refraction, a rough (GGX) specular lobe and a diffuse texture.

#include <cstdint>

#include "glint/math/vec3.h"

namespace glint {

/// The ambient light level Glint assumes for materials of model files (MTL, glTF) and for the
/// materials it gives models itself: their ambient colour is this times Ka, or times their
/// diffuse colour when they have no Ka. OpenGL's default global ambient.
constexpr double kMtlAmbientLight = 0.2;

struct Material {
    Vec3 ambient{0.2};  ///< Added unshadowed; the course default is 0.2 grey.
    Vec3 diffuse;
    Vec3 specular;  ///< Blinn-Phong colour and the weight of the mirror ray.
    Vec3 emission;
    double shininess = 0;
    /// Weight of the light carried through the surface (refracted), split with the reflected
    /// ray by Fresnel. Zero (the default) for opaque materials.
    Vec3 transmission;
    double ior = 1.5;  ///< Index of refraction inside the object (outside is 1).
    /// GGX roughness alpha in [0, 1]: 0 (the default) is the course's perfect mirror and
    /// Blinn-Phong highlight; above 0 the specular term is a GGX microfacet lobe.
    double roughness = 0;
    /// Emission only towards the front face (the geometry of area lights).
    bool frontEmissionOnly = false;
    /// Id of the texture whose value replaces `diffuse` at each hit (Scene::texture); 0: none.
    uint32_t texture = 0;
    /// Id of the physically based material the path tracer renders instead (Scene::pbr);
    /// 0: none, the path tracer makes its BSDF from this material.
    uint32_t pbr = 0;
    /// Id of the medium inside closed surfaces of this material (Scene::medium); 0: none. The
    /// path tracer enters it where a path crosses such a surface inwards, and returns to the
    /// scene's fog where it crosses outwards.
    uint32_t interior = 0;
    /// Only a medium's boundary: rays pass through such surfaces unchanged (pbrt's
    /// "interface" material), changing medium; they are not drawn.
    bool interface = false;

    bool transmissive() const { return !(transmission == Vec3(0)); }

    bool operator==(const Material&) const = default;
};

}  // namespace glint
