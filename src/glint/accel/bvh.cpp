#include "glint/accel/bvh.h"

#include <chrono>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

#include "glint/accel/bvh_build.h"
#include "glint/accel/bvh_kernels.h"
#include "glint/core/system.h"

namespace glint {

Isa Bvh::bestIsa() {
    static const Isa best = [] {
        const char* forced = std::getenv("GLINT_ISA");
        if (forced && std::strcmp(forced, "portable") == 0) return Isa::Portable;
#if GLINT_HAVE_AVX2
        if (__builtin_cpu_supports("avx2")) return Isa::Avx2;
#endif
        return Isa::Portable;
    }();
    return best;
}

const char* Bvh::name(Isa isa) {
    switch (isa) {
        case Isa::Avx2:
            return "avx2";
        case Isa::Portable:
            return "portable";
        case Isa::Auto:
            break;
    }
    return name(bestIsa());
}

const char* Bvh::isa() { return name(bestIsa()); }

void Bvh::build(const Primitives& prims, const BvhBuildOptions& options) {
    auto start = std::chrono::steady_clock::now();
    isa_ = options.isa == Isa::Auto ? bestIsa() : options.isa;
#if !GLINT_HAVE_AVX2
    if (isa_ == Isa::Avx2) throw std::invalid_argument("this build has no AVX2 kernels");
#endif
    int threads = options.threads > 0 ? options.threads : hardwareThreads();
    bvh::BuildSummary s = bvh::build(prims, threads, data_);
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
    if (isa_ == Isa::Avx2) return bvh::avx2::intersect(data_, ray, hit);
#endif
    return bvh::portable::intersect(data_, ray, hit);
}

bool Bvh::occluded(const TraversalRay& ray) const {
#if GLINT_HAVE_AVX2
    if (isa_ == Isa::Avx2) return bvh::avx2::occluded(data_, ray);
#endif
    return bvh::portable::occluded(data_, ray);
}

void Bvh::intersect8(const RayPacket8& rays, HitPacket8& hits) const {
#if GLINT_HAVE_AVX2
    if (isa_ == Isa::Avx2) return bvh::avx2::intersect8(data_, rays, hits);
#endif
    bvh::portable::intersect8(data_, rays, hits);
}

}  // namespace glint
