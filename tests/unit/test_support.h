#pragma once
// Small helpers shared by the unit tests.

#include <gtest/gtest.h>

#include "glint/math/vec3.h"
#include "glint/scene/material.h"

namespace glint::test {

/// Expects every component of `a` within `eps` of `b`.
inline void expectNear(const Vec3& a, const Vec3& b, double eps = 1e-12) {
    EXPECT_NEAR(a.x, b.x, eps);
    EXPECT_NEAR(a.y, b.y, eps);
    EXPECT_NEAR(a.z, b.z, eps);
}

/// A material with the given terms; emission black.
inline Material makeMaterial(const Vec3& ambient, const Vec3& diffuse = {},
                             const Vec3& specular = {}, double shininess = 1) {
    Material m;
    m.ambient = ambient;
    m.diffuse = diffuse;
    m.specular = specular;
    m.shininess = shininess;
    return m;
}

}  // namespace glint::test
