#pragma once
/// Glint's acceleration structure: an 8-wide BVH over triangles, (transformed) spheres, boxes,
/// cylinders, cones and disks, and instances of shared meshes, built with binned SAH on a thread
/// pool and traversed by SIMD kernels chosen for the CPU (or by the caller: BvhBuildOptions).
/// A shared mesh is triangles in their own space with a Bvh of their own; an instance places it
/// under a transform, as one record in this tree whose test searches the mesh's tree: a
/// two-level BVH (docs/design.md, "Instancing"). Infinite planes cannot have finite bounds: they
/// are kept in a short list beside the tree, and so are moving primitives (Primitives::
/// setMotion), tested at the calling thread's shutter time (math/motion.h); intersect,
/// occluded and intersect8 test them too, so every caller gets them; they are not part of
/// bounds().
/// Layout: bvh_layout.h; build: bvh_build.h (and the files it names); kernels: bvh_isa_*.cpp,
/// bvh_traverse.inl.

#include <cstdint>
#include <string_view>
#include <vector>

#include "glint/accel/bvh_layout.h"
#include "glint/geometry/primitives.h"

namespace glint {

/// Instruction sets the traversal kernels exist for.
enum class Isa { Auto, Portable, Avx2, Simd128 };

class Bvh;
class ThreadPool;

struct BvhBuildOptions {
    int threads = 0;      ///< Build threads when `pool` is null; 0 means all hardware threads.
    Isa isa = Isa::Auto;  ///< Kernels to traverse with; Auto: the best this CPU runs.
    /// The BVHs of the primitives' shared meshes, in their order (Primitives::sharedMesh):
    /// instances are searched through them. Each must use the same kernels and outlive this
    /// BVH.
    std::vector<const Bvh*> sharedMeshes = {};
    /// The threads to build on (the calling thread is one of them); null: a pool of `threads`
    /// made for this build. The tree does not depend on the thread count.
    ThreadPool* pool = nullptr;
};

struct BvhStats {
    uint32_t nodes = 0;  ///< 8-wide nodes.
    uint32_t leaves = 0;
    uint32_t maxDepth = 0;     ///< Levels of nodes.
    uint32_t maxLeafSize = 0;  ///< Primitives in the largest leaf.
    size_t bytes = 0;          ///< Everything traversal reads: nodes and leaf data.
    double buildSeconds = 0;   ///< Of the last build, or refit.
    bool refitted = false;     ///< The last change was a refit (Bvh::refit), not a build.
    /// The summed areas of the nodes' boxes over the root's, as built (bvh::relativeArea).
    double builtArea = 0;
};

class Bvh {
  public:
    /// Builds over `prims`. The BVH keeps its own copy of what traversal needs; `prims`
    /// only has to live while building. Throws std::invalid_argument for kernels this CPU
    /// cannot run, or without a BVH for each shared mesh.
    void build(const Primitives& prims, const BvhBuildOptions& options = {});
    /// Fits this BVH to `prims`: the primitives it was built over, moved (the next frame of an
    /// animation), with the same counts of each kind and the same ones moving over the
    /// shutter. The tree keeps its shape, and its leaves and boxes take the primitives' new
    /// places; searches find exactly what a fresh build's would. Returns false, changing
    /// nothing, for primitives of other counts, or kernels or shared meshes other than
    /// those it was built with: build then. As things move from where the tree was built, it
    /// grows slower to search (relativeArea() against stats().builtArea says by how much).
    bool refit(const Primitives& prims, const BvhBuildOptions& options = {});
    /// The summed areas of the nodes' boxes over the root's, now (bvh::relativeArea).
    double relativeArea() const;

    /// Closest hit with tMin < t < min(ray.tMax, hit.t); fills `hit` and returns true if any.
    /// Among hits at exactly the same distance the lowest primitive id wins, so the result
    /// does not depend on traversal order or instruction set.
    bool intersect(const Ray& ray, Hit& hit) const { return intersect(TraversalRay(ray), hit); }
    bool intersect(const TraversalRay& ray, Hit& hit) const;
    /// Whether anything lies strictly between tMin and tMax (any hit, not the closest).
    bool occluded(const Ray& ray) const { return occluded(TraversalRay(ray)); }
    bool occluded(const TraversalRay& ray) const;
    /// Closest hits of the active rays of a packet; the same results as `intersect` per ray.
    void intersect8(const RayPacket8& rays, HitPacket8& hits) const;

    const BvhStats& stats() const { return stats_; }
    /// Bounds of everything in the tree (empty if nothing): planes are not included.
    Bounds3f bounds() const;
    const bvh::BvhData& data() const { return data_; }
    /// The kernels this BVH traverses with.
    Isa kernels() const { return isa_; }

    /// The best kernels this CPU runs (in WebAssembly: the SIMD128 ones, always).
    static Isa bestIsa();
    /// "avx2", "simd128" or "portable": the kernels a default-built BVH uses on this machine.
    static const char* isa();
    static const char* name(Isa isa);
    /// The kernels called `name` (as name() spells them), Auto for anything else ("auto").
    static Isa named(std::string_view name);

  private:
    /// intersect and occluded for scenes with planes or moving primitives, out of line: the
    /// other calls stay plain tail calls into the kernels.
    [[gnu::noinline]] bool intersectWithPlanes(const TraversalRay& ray, Hit& hit) const;
    [[gnu::noinline]] bool occludedWithPlanes(const TraversalRay& ray) const;

    /// What build and refit both do beside the tree: the shared meshes' trees, the planes
    /// and the moving primitives, from `prims`.
    void placeBeside(const Primitives& prims, const BvhBuildOptions& options);
    /// Counts of each kind of primitive, and the ids of moving ones: what a refit must match.
    std::vector<uint32_t> shapeOf(const Primitives& prims) const;

    bvh::BvhData data_;
    BvhStats stats_;
    std::vector<uint32_t> builtShape_;  ///< shapeOf() the primitives it was built over.
    Bounds3f bounds_;
    Isa isa_ = Isa::Portable;
    /// The kernels to call, or Auto when the scene has planes: one comparison picks the way.
    Isa route_ = Isa::Portable;
};

}  // namespace glint
