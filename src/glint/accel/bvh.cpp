#include "glint/accel/bvh.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>

#include "glint/accel/bvh_build.h"
#include "glint/accel/bvh_kernels.h"
#include "glint/core/parallel.h"

namespace glint {
namespace {

/// Planes have no finite bounds, so they are not in the tree: every query tests them here,
/// beside it, by the same closerHit rule. Scalar code, the same whatever the kernels.
bool hitPlanes(const bvh::BvhData& d, const TraversalRay& ray, Hit& hit) {
    bool found = false;
    for (size_t i = 0; i < d.planes.size(); ++i) {
        float t;
        if (intersectPlane(d.planes[i], ray, t) && closerHit(t, d.planeIds[i], hit))
            hit = {t, d.planeIds[i]}, found = true;
    }
    return found;
}

bool planeOccludes(const bvh::BvhData& d, const TraversalRay& ray) {
    for (const PlaneSearch& p : d.planes) {
        float t;
        if (intersectPlane(p, ray, t)) return true;
    }
    return false;
}

/// The tree searches of kernels `isa`.
bool treeIntersect(Isa isa, const bvh::BvhData& d, const TraversalRay& ray, Hit& hit) {
#if GLINT_HAVE_AVX2
    if (isa == Isa::Avx2) return bvh::avx2::intersect(d, ray, hit);
#endif
#if GLINT_HAVE_SIMD128
    if (isa == Isa::Simd128) return bvh::simd128::intersect(d, ray, hit);
#endif
    return bvh::portable::intersect(d, ray, hit);
}

bool treeOccluded(Isa isa, const bvh::BvhData& d, const TraversalRay& ray) {
#if GLINT_HAVE_AVX2
    if (isa == Isa::Avx2) return bvh::avx2::occluded(d, ray);
#endif
#if GLINT_HAVE_SIMD128
    if (isa == Isa::Simd128) return bvh::simd128::occluded(d, ray);
#endif
    return bvh::portable::occluded(d, ray);
}

/// Moving primitive `m` at the calling thread's shutter time: the ray mapped to where the
/// primitive was added, and tested there (an instance by its mesh's tree). Closest hit: updates
/// `hit` by the closerHit rule; any hit (`anyHit`): returns true at the first.
bool hitMoving(Isa isa, const bvh::BvhData& d, const bvh::BvhData::Moving& m,
               const TraversalRay& ray, Hit& hit, bool anyHit) {
    const float best = anyHit ? ray.tMax : std::min(hit.t, ray.tMax);
    if (!(boxEntry(m.bounds, ray, best) <= best)) return false;
    const Transform delta = m.path.delta(shutterTime());
    const TraversalRay local(Vec3f(delta.inversePoint(Vec3(ray.origin))),
                             Vec3f(delta.inverseVector(Vec3(ray.dir))), ray.tMin, ray.tMax);
    if (m.search.kind == ShapeKind::Instance) {
        Vec3f o, dir;
        m.search.map(local, o, dir);
        // Up to and including the best hit so far: a tie goes to the lower id.
        const float tMax = !anyHit && hit.t < ray.tMax ? std::nextafter(hit.t, ray.tMax) : ray.tMax;
        const TraversalRay inMesh(o, dir, ray.tMin, tMax);
        const bvh::BvhData& mesh = *d.meshes[m.search.mesh()];
        Hit sub;
        if (const DeformingMesh* deform = d.deforming[m.search.mesh()]) {
            if (anyHit) return deform->occluded(inMesh, shutterTime());
            if (!deform->intersect(inMesh, shutterTime(), sub) || !closerHit(sub.t, m.id, hit))
                return false;
            hit = {sub.t, m.id, sub.primId};
            return true;
        }
        if (anyHit) return treeOccluded(isa, mesh, inMesh);
        if (!treeIntersect(isa, mesh, inMesh, sub) || !closerHit(sub.t, m.id, hit)) return false;
        hit = {sub.t, m.id, sub.primId};
        return true;
    }
    float t;
    if (!intersectShape(m.search, local, t)) return false;
    if (anyHit) return true;
    if (!closerHit(t, m.id, hit)) return false;
    hit = {t, m.id};
    return true;
}

/// Everything beside the tree: planes, then moving primitives.
bool hitBeside(Isa isa, const bvh::BvhData& d, const TraversalRay& ray, Hit& hit) {
    bool found = hitPlanes(d, ray, hit);
    for (const bvh::BvhData::Moving& m : d.moving) found |= hitMoving(isa, d, m, ray, hit, false);
    return found;
}

bool besideOccludes(Isa isa, const bvh::BvhData& d, const TraversalRay& ray) {
    if (planeOccludes(d, ray)) return true;
    Hit unused;
    for (const bvh::BvhData::Moving& m : d.moving)
        if (hitMoving(isa, d, m, ray, unused, true)) return true;
    return false;
}

}  // namespace

Isa Bvh::bestIsa() {
    static const Isa best = [] {
#if GLINT_HAVE_AVX2
        if (__builtin_cpu_supports("avx2")) return Isa::Avx2;
#endif
#if GLINT_HAVE_SIMD128
        return Isa::Simd128;  // compiled with -msimd128: every engine that loads it runs it
#endif
        return Isa::Portable;
    }();
    return best;
}

const char* Bvh::name(Isa isa) {
    switch (isa) {
        case Isa::Avx2:
            return "avx2";
        case Isa::Simd128:
            return "simd128";
        case Isa::Portable:
            return "portable";
        case Isa::Auto:
            break;
    }
    return name(bestIsa());
}

Isa Bvh::named(std::string_view name) {
    for (Isa isa : {Isa::Portable, Isa::Avx2, Isa::Simd128})
        if (name == Bvh::name(isa)) return isa;
    return Isa::Auto;
}

const char* Bvh::isa() { return name(bestIsa()); }

void Bvh::build(const Primitives& prims, const BvhBuildOptions& options) {
    auto start = std::chrono::steady_clock::now();
    isa_ = options.isa == Isa::Auto ? bestIsa() : options.isa;
    if (isa_ == Isa::Avx2 && bestIsa() != Isa::Avx2)
        throw std::invalid_argument(
            "the AVX2 kernels need a CPU with AVX2 (and a build with them)");
    if (isa_ == Isa::Simd128 && bestIsa() != Isa::Simd128)
        throw std::invalid_argument("the SIMD128 kernels exist in the WebAssembly build only");
    if (options.sharedMeshes.size() != prims.sharedMeshCount())
        throw std::invalid_argument("a BVH is needed for every shared mesh");
    for (const Bvh* mesh : options.sharedMeshes)
        if (mesh->isa_ != isa_)
            throw std::invalid_argument("a shared mesh's BVH uses other kernels");
    std::optional<ThreadPool> ownPool;
    ThreadPool& pool = options.pool ? *options.pool : ownPool.emplace(options.threads);
    bvh::BuildSummary s = bvh::build(prims, pool, data_);
    placeBeside(prims, options);
    builtShape_ = shapeOf(prims);
    bounds_ = s.bounds;
    stats_ = {};
    stats_.nodes = static_cast<uint32_t>(data_.nodes.size());
    stats_.leaves = s.leaves;
    stats_.maxDepth = s.maxDepth;
    stats_.maxLeafSize = s.maxLeafSize;
    stats_.bytes = data_.bytes();
    stats_.builtArea = bvh::relativeArea(data_);
    stats_.buildSeconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

bool Bvh::refit(const Primitives& prims, const BvhBuildOptions& options) {
    auto start = std::chrono::steady_clock::now();
    const Isa isa = options.isa == Isa::Auto ? bestIsa() : options.isa;
    if (isa != isa_ || builtShape_.empty() || shapeOf(prims) != builtShape_ ||
        options.sharedMeshes.size() != prims.sharedMeshCount())
        return false;
    for (const Bvh* mesh : options.sharedMeshes)
        if (mesh->isa_ != isa_) return false;
    bounds_ = bvh::refit(prims, data_);
    placeBeside(prims, options);
    stats_.refitted = true;
    stats_.buildSeconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return true;
}

double Bvh::relativeArea() const { return bvh::relativeArea(data_); }

std::vector<uint32_t> Bvh::shapeOf(const Primitives& prims) const {
    std::vector<uint32_t> shape = {prims.triangleCount(), prims.sphereCount(),
                                   prims.shapeCount(),    prims.instanceCount(),
                                   prims.planeCount(),    prims.sharedMeshCount()};
    if (prims.hasMotion())
        for (uint32_t id = 0; id < prims.boundedCount(); ++id)
            if (prims.motion(id)) shape.push_back(id);
    return shape;
}

void Bvh::placeBeside(const Primitives& prims, const BvhBuildOptions& options) {
    data_.meshes.clear();
    data_.deforming.clear();
    for (uint32_t i = 0; i < options.sharedMeshes.size(); ++i) {
        data_.meshes.push_back(&options.sharedMeshes[i]->data_);
        data_.deforming.push_back(prims.sharedMesh(i).deformation());
    }
    data_.planes.clear();
    data_.planeIds.clear();
    for (uint32_t id = prims.boundedCount(); id < prims.size(); ++id) {
        data_.planes.push_back(prims.planeSearch(id));
        data_.planeIds.push_back(id);
    }
    data_.moving.clear();
    if (prims.hasMotion())
        for (uint32_t id = 0; id < prims.boundedCount(); ++id)
            if (const MotionPath* m = prims.motion(id))
                data_.moving.push_back({id, prims.bounds(id), prims.shapeSearch(id), *m});
    route_ = data_.planes.empty() && data_.moving.empty() ? isa_ : Isa::Auto;
}

Bounds3f Bvh::bounds() const { return bounds_; }

bool Bvh::intersect(const TraversalRay& ray, Hit& hit) const {
#if GLINT_HAVE_AVX2
    if (route_ == Isa::Avx2) return bvh::avx2::intersect(data_, ray, hit);
#endif
#if GLINT_HAVE_SIMD128
    if (route_ == Isa::Simd128) return bvh::simd128::intersect(data_, ray, hit);
#endif
    if (route_ == Isa::Portable) return bvh::portable::intersect(data_, ray, hit);
    return intersectWithPlanes(ray, hit);
}

bool Bvh::occluded(const TraversalRay& ray) const {
#if GLINT_HAVE_AVX2
    if (route_ == Isa::Avx2) return bvh::avx2::occluded(data_, ray);
#endif
#if GLINT_HAVE_SIMD128
    if (route_ == Isa::Simd128) return bvh::simd128::occluded(data_, ray);
#endif
    if (route_ == Isa::Portable) return bvh::portable::occluded(data_, ray);
    return occludedWithPlanes(ray);
}

/// hitBeside for each active ray of a packet (out of line: packets without planes or motion
/// do not pay for its registers).
[[gnu::noinline]] static void hitBeside8(Isa isa, const bvh::BvhData& d, const RayPacket8& rays,
                                         HitPacket8& hits) {
    for (int i = 0; i < 8; ++i) {
        if (!(rays.active >> i & 1)) continue;
        Hit h = hits[i];
        if (hitBeside(isa, d, rays.rays[i], h)) hits.set(i, h);
    }
}

void Bvh::intersect8(const RayPacket8& rays, HitPacket8& hits) const {
    if (route_ == Isa::Auto) hitBeside8(isa_, data_, rays, hits);
#if GLINT_HAVE_AVX2
    if (isa_ == Isa::Avx2) return bvh::avx2::intersect8(data_, rays, hits);
#endif
#if GLINT_HAVE_SIMD128
    if (isa_ == Isa::Simd128) return bvh::simd128::intersect8(data_, rays, hits);
#endif
    bvh::portable::intersect8(data_, rays, hits);
}

bool Bvh::intersectWithPlanes(const TraversalRay& ray, Hit& hit) const {
    // Beside the tree first: a hit there bounds the search of the tree.
    bool found = hitBeside(isa_, data_, ray, hit);
    return treeIntersect(isa_, data_, ray, hit) || found;
}

bool Bvh::occludedWithPlanes(const TraversalRay& ray) const {
    return besideOccludes(isa_, data_, ray) || treeOccluded(isa_, data_, ray);
}

}  // namespace glint
