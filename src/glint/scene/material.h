#pragma once
/// The course's material: OpenGL-style terms plus the mirror weight (= specular).

#include "glint/math/vec3.h"

namespace glint {

struct Material {
    Vec3 ambient{0.2};  ///< Added unshadowed; the course default is 0.2 grey.
    Vec3 diffuse;
    Vec3 specular;  ///< Blinn-Phong colour and the weight of the mirror ray.
    Vec3 emission;
    double shininess = 0;

    bool operator==(const Material&) const = default;
};

}  // namespace glint
