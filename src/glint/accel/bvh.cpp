#include "glint/accel/bvh.h"

#include <chrono>
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

/// hitPlanes for each active ray of a packet (out of line: packets without planes do not pay
/// for its registers).
[[gnu::noinline]] void hitPlanes8(const bvh::BvhData& d, const RayPacket8& rays, HitPacket8& hits) {
    for (int i = 0; i < 8; ++i) {
        if (!(rays.active >> i & 1)) continue;
        Hit h = hits[i];
        if (hitPlanes(d, rays.rays[i], h)) hits.set(i, h);
    }
}

bool planeOccludes(const bvh::BvhData& d, const TraversalRay& ray) {
    for (const PlaneSearch& p : d.planes) {
        float t;
        if (intersectPlane(p, ray, t)) return true;
    }
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
    std::optional<ThreadPool> ownPool;
    ThreadPool& pool = options.pool ? *options.pool : ownPool.emplace(options.threads);
    bvh::BuildSummary s = bvh::build(prims, pool, data_);
    data_.meshes.clear();
    for (const Bvh* mesh : options.sharedMeshes) {
        if (mesh->isa_ != isa_)
            throw std::invalid_argument("a shared mesh's BVH uses other kernels");
        data_.meshes.push_back(&mesh->data_);
    }
    for (uint32_t id = prims.boundedCount(); id < prims.size(); ++id) {
        data_.planes.push_back(prims.planeSearch(id));
        data_.planeIds.push_back(id);
    }
    route_ = data_.planes.empty() ? isa_ : Isa::Auto;
    bounds_ = s.bounds;
    stats_ = {};
    stats_.nodes = static_cast<uint32_t>(data_.nodes.size());
    stats_.leaves = s.leaves;
    stats_.maxDepth = s.maxDepth;
    stats_.maxLeafSize = s.maxLeafSize;
    stats_.bytes = data_.bytes();
    stats_.buildSeconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
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

void Bvh::intersect8(const RayPacket8& rays, HitPacket8& hits) const {
    if (route_ == Isa::Auto) hitPlanes8(data_, rays, hits);
#if GLINT_HAVE_AVX2
    if (isa_ == Isa::Avx2) return bvh::avx2::intersect8(data_, rays, hits);
#endif
#if GLINT_HAVE_SIMD128
    if (isa_ == Isa::Simd128) return bvh::simd128::intersect8(data_, rays, hits);
#endif
    bvh::portable::intersect8(data_, rays, hits);
}

bool Bvh::intersectWithPlanes(const TraversalRay& ray, Hit& hit) const {
    // Planes first: a hit on one bounds the search of the tree.
    bool found = hitPlanes(data_, ray, hit);
#if GLINT_HAVE_AVX2
    if (isa_ == Isa::Avx2) return bvh::avx2::intersect(data_, ray, hit) || found;
#endif
#if GLINT_HAVE_SIMD128
    if (isa_ == Isa::Simd128) return bvh::simd128::intersect(data_, ray, hit) || found;
#endif
    return bvh::portable::intersect(data_, ray, hit) || found;
}

bool Bvh::occludedWithPlanes(const TraversalRay& ray) const {
    if (planeOccludes(data_, ray)) return true;
#if GLINT_HAVE_AVX2
    if (isa_ == Isa::Avx2) return bvh::avx2::occluded(data_, ray);
#endif
#if GLINT_HAVE_SIMD128
    if (isa_ == Isa::Simd128) return bvh::simd128::occluded(data_, ray);
#endif
    return bvh::portable::occluded(data_, ray);
}

}  // namespace glint
