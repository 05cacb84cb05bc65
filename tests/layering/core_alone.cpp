// Links every object file of glint_core, and nothing else: the build fails if the core layers
// (math to render) reach for a file format or a third-party library (docs/design.md, "Layers").
// It renders a one-sphere scene built in code, so the program also does something.

#include <cstdio>

#include "glint/render/renderer.h"

int main() {
    glint::Scene scene;
    scene.width = scene.height = 8;
    scene.camera = glint::CameraSpec{{0, 0, 4}, {0, 0, 0}, {0, 1, 0}, 45};
    glint::Material m;
    m.diffuse = glint::Vec3(1);
    glint::Sphere sphere{{0, 0, 0}, 1, {}};
    scene.primitives.addSphere(sphere, scene.addMaterial(m));
    scene.prepare();
    glint::RenderOptions options;
    options.threads = 1;
    glint::RenderResult result = glint::render(scene, options);
    // The centre pixel sees the sphere: its ambient term (0.2) at least.
    double centre = result.film.at(4, 4).x;
    std::printf("glint_core alone: centre pixel %.3f\n", centre);
    return centre > 0.1 ? 0 : 1;
}
