#include "glint/scene/scene.h"

#include <optional>

#include "glint/core/parallel.h"
#include "glint/core/spawn.h"
#include "glint/math/bits.h"
#include "glint/math/rng.h"

namespace glint {

uint32_t Scene::addMaterial(const Material& m) {
    if (materials.empty() || !(materials.back() == m)) materials.push_back(m);
    return static_cast<uint32_t>(materials.size() - 1);
}

size_t Scene::estimateBytes(size_t triangles, size_t spheres, size_t shapes, size_t normals,
                            size_t uvs) {
    // Measured BVH sizes are 57 bytes per triangle; 80 allows for poorly filled leaf blocks.
    constexpr size_t kBvhPerTriangle = 80, kBvhPerShape = 96;
    constexpr size_t kBuildPerPrimitive = 48;  // bounds, ids and temporary nodes
    size_t perTriangle = sizeof(Triangle) + sizeof(uint32_t) + kBvhPerTriangle + kBuildPerPrimitive;
    size_t perNormals = sizeof(std::array<Vec3, 3>) + sizeof(uint32_t);
    // Triangles with texture coordinates also need the shading-normal index (kFlat).
    size_t perUvs = sizeof(std::array<TexCoord, 3>) + 2 * sizeof(uint32_t);
    size_t perSphere =
        sizeof(Sphere) + sizeof(ShapeSearch) + sizeof(uint32_t) + kBvhPerShape + kBuildPerPrimitive;
    size_t perShape =
        sizeof(Shape) + sizeof(ShapeSearch) + sizeof(uint32_t) + kBvhPerShape + kBuildPerPrimitive;
    return triangles * perTriangle + normals * perNormals + uvs * perUvs + spheres * perSphere +
           shapes * perShape;
}

uint32_t Scene::addSharedMesh(Primitives mesh) {
    auto shared = std::make_unique<SharedMesh>();
    shared->primitives = std::move(mesh);
    uint32_t index = primitives.addSharedMesh(shared->primitives);
    sharedMeshes_.push_back(std::move(shared));
    return index;
}

size_t Scene::sharedTriangleCount() const {
    size_t n = 0;
    for (const auto& m : sharedMeshes_) n += m->primitives.triangleCount();
    return n;
}

size_t Scene::sharedBvhBytes() const {
    size_t n = 0;
    for (const auto& m : sharedMeshes_) n += m->bvh.stats().bytes;
    return n;
}

namespace {

/// Takes `kept` as `bvh` if it refits to `prims` and stays within `growth` of its built
/// quality; else builds `bvh`.
void refitOrBuild(Bvh& bvh, Bvh* kept, const Primitives& prims, const BvhBuildOptions& options,
                  double growth) {
    if (kept && kept->refit(prims, options) &&
        kept->relativeArea() <= kept->stats().builtArea * growth) {
        bvh = std::move(*kept);
        return;
    }
    bvh.build(prims, options);
}

}  // namespace

void Scene::prepare(const PrepareOptions& options) {
    std::optional<ThreadPool> ownPool;
    ThreadPool& pool = options.pool ? *options.pool : ownPool.emplace();
    const BvhBuildOptions meshes{.isa = options.kernels, .pool = &pool};
    BvhBuildOptions scene = meshes;
    FrameAccel* reuse = options.reuse;
    if (reuse && (!reuse->kept || reuse->meshes.size() != sharedMeshes_.size())) reuse = nullptr;
    for (size_t i = 0; i < sharedMeshes_.size(); ++i) {
        SharedMesh& m = *sharedMeshes_[i];
        refitOrBuild(m.bvh, reuse ? &reuse->meshes[i] : nullptr, m.primitives, meshes,
                     options.refitGrowth);
        scene.sharedMeshes.push_back(&m.bvh);
    }
    refitOrBuild(bvh_, reuse ? &reuse->scene : nullptr, primitives, scene, options.refitGrowth);
    if (options.reuse) *options.reuse = {};
    Bounds3f b = bvh_.bounds();
    spawnOffset_ =
        sceneSpawnOffset(b.empty() ? 1.0 : static_cast<double>(maxComponent(b.diagonal())));
    cutouts_ = filtersCamera_ = false;
    for (const PbrMaterial& m : pbrMaterials) {
        cutouts_ = cutouts_ || m.cutsOut();
        filtersCamera_ = filtersCamera_ || !m.doubleSided || !m.cameraVisible;
    }
    prepared_ = true;
}

void Scene::keepAccel(FrameAccel& into) {
    into = {};
    if (!prepared_) return;
    into.scene = std::move(bvh_);
    for (const auto& m : sharedMeshes_) into.meshes.push_back(std::move(m->bvh));
    into.kept = true;
    bvh_ = {};
    prepared_ = false;
}

bool Scene::cutOut(const Ray& ray, const Hit& hit, bool cameraRay) const {
    const SurfaceInteraction si = primitives.interaction(ray, hit);
    const Material& m = materials[si.material];
    if (m.pbr == 0) return false;
    const PbrMaterial& pm = pbr(m.pbr);
    if (pm.unlit && !cameraRay) return true;
    if (cameraRay && !pm.cameraVisible) return true;
    if (cameraRay && !pm.doubleSided && dot(ray.dir, si.ng) > 0) return true;
    if (pm.alphaMode == AlphaMode::Opaque) return false;
    const double alpha = opacityAt(pm, si);
    if (pm.alphaMode == AlphaMode::Mask) return alpha < pm.alphaCutoff;
    // Blend: the hit counts with probability alpha, decided by a hash of the ray and the
    // primitive, so that the same ray always sees the same surfaces.
    uint64_t h = mixBits(bitCast<uint64_t>(ray.origin.x) ^ hit.primId);
    h = mixBits(h ^ bitCast<uint64_t>(ray.origin.y) ^ (uint64_t(hit.subId) << 32));
    h = mixBits(h ^ bitCast<uint64_t>(ray.origin.z));
    h = mixBits(h ^ bitCast<uint64_t>(ray.dir.x));
    h = mixBits(h ^ bitCast<uint64_t>(ray.dir.y) ^ bitCast<uint64_t>(ray.dir.z));
    const double u = static_cast<double>(h >> 11) * 0x1p-53;
    return alpha <= u;
}

bool Scene::filterHit(const Ray& ray, Hit& hit, bool cameraRay) const {
    Ray r = ray;
    // Each step moves past a hit; a pathological stack of cut-out layers ends the walk (the
    // last hit then counts).
    for (int layer = 0; layer < kMaxCutoutLayers; ++layer) {
        if (!cutOut(r, hit, cameraRay)) return true;
        r.tMin = static_cast<double>(hit.t);
        hit = Hit{};
        if (!bvh_.intersect(r, hit)) return false;
    }
    return true;
}

}  // namespace glint
