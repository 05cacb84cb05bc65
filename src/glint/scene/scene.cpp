#include "glint/scene/scene.h"

#include "glint/core/spawn.h"

namespace glint {

uint32_t Scene::addMaterial(const Material& m) {
    if (materials.empty() || !(materials.back() == m)) materials.push_back(m);
    return static_cast<uint32_t>(materials.size() - 1);
}

void Scene::prepare() {
    bvh_.build(primitives);
    Bounds3f b = bvh_.bounds();
    spawnOffset_ =
        sceneSpawnOffset(b.empty() ? 1.0 : static_cast<double>(maxComponent(b.diagonal())));
    prepared_ = true;
}

}  // namespace glint
