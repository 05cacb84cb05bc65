#pragma once
/// Traversal kernels, one set per instruction set; Bvh picks one when it is built.

#include "glint/accel/bvh_layout.h"
#include "glint/core/ray.h"

namespace glint::bvh {

/// Portable C++: the reference every other kernel set must match bit for bit.
namespace portable {
bool intersect(const BvhData& d, const TraversalRay& ray, Hit& hit);
bool occluded(const BvhData& d, const TraversalRay& ray);
void intersect8(const BvhData& d, const RayPacket8& rays, HitPacket8& hits);
}  // namespace portable

#if GLINT_HAVE_AVX2
/// AVX2: eight boxes per instruction, four triangles per SSE instruction.
namespace avx2 {
bool intersect(const BvhData& d, const TraversalRay& ray, Hit& hit);
bool occluded(const BvhData& d, const TraversalRay& ray);
void intersect8(const BvhData& d, const RayPacket8& rays, HitPacket8& hits);
}  // namespace avx2
#endif

#if GLINT_HAVE_SIMD128
/// WebAssembly SIMD128: eight boxes as two halves of four, four triangles per instruction.
namespace simd128 {
bool intersect(const BvhData& d, const TraversalRay& ray, Hit& hit);
bool occluded(const BvhData& d, const TraversalRay& ray);
void intersect8(const BvhData& d, const RayPacket8& rays, HitPacket8& hits);
}  // namespace simd128
#endif

}  // namespace glint::bvh
