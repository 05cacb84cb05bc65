#pragma once
/// The tree the BVH builder grows (8-wide nodes that hold their children's boxes, leaves as ref
/// ranges), before flatten() lays it out as bvh_layout.h describes. Internal to the builder
/// (bvh_build*.cpp).

#include <atomic>
#include <cstdint>
#include <memory>
#include <stdexcept>

#include "glint/accel/bvh_build.h"
#include "glint/accel/bvh_build_refs.h"
#include "glint/core/huge_pages.h"

namespace glint::bvh::builder {

/// A child while building: a node id, or a leaf: kLeafBit | the first of `size` refs.
struct ChildRef {
    uint32_t ref = kEmpty;
    uint32_t size = 0;
    bool shapes = false;  ///< A leaf of shapes (leaves hold triangles or shapes, not both).
};

/// An 8-wide node while building. Nodes are written only by the task that builds them, and
/// leaves live in their parent: building shares no counters or arrays between threads.
struct TmpNode {
    Bounds3f bounds[kWidth];
    ChildRef child[kWidth];
    uint32_t count = 0;
};

/// Nodes allocated from many threads: fixed-size chunks, never moved.
class NodePool {
  public:
    uint32_t allocate() {
        uint32_t id = next_.fetch_add(1, std::memory_order_relaxed);
        uint32_t chunk = id >> kChunkBits;
        if (chunk >= kMaxChunks) throw std::length_error("BVH too large");
        if (!chunks_[chunk].load(std::memory_order_acquire)) {
            // The first thread to need the chunk installs it; any other drops its own.
            auto fresh = std::make_unique<TmpNode[]>(size_t{1} << kChunkBits);
            TmpNode* expected = nullptr;
            if (chunks_[chunk].compare_exchange_strong(expected, fresh.get(),
                                                       std::memory_order_acq_rel))
                fresh.release();
        }
        return id;
    }
    TmpNode& operator[](uint32_t id) {
        return chunks_[id >> kChunkBits].load(std::memory_order_relaxed)[id & kChunkMask];
    }
    const TmpNode& operator[](uint32_t id) const {
        return chunks_[id >> kChunkBits].load(std::memory_order_relaxed)[id & kChunkMask];
    }

    NodePool() = default;
    NodePool(const NodePool&) = delete;
    NodePool& operator=(const NodePool&) = delete;
    ~NodePool() {
        for (uint32_t c = 0; c < kMaxChunks; ++c) delete[] chunks_[c].load();
    }

  private:
    static constexpr int kChunkBits = 12;
    static constexpr uint32_t kChunkMask = (1u << kChunkBits) - 1;
    static constexpr uint32_t kMaxChunks = 1u << 19;
    std::atomic<uint32_t> next_{0};
    std::unique_ptr<std::atomic<TmpNode*>[]> chunks_ =
        std::make_unique<std::atomic<TmpNode*>[]>(kMaxChunks);
};

/// Lays the tree under `root` out depth first into `out` (resized to fit), turning leaves into
/// leaf blocks and records of `prims` (refs name them); the root's subtrees are laid out in
/// parallel at positions computed beforehand, so the layout does not depend on the threads.
/// Returns the root's reference; adds leaves, depth and leaf size to `summary`.
NodeRef flatten(const ChildRef& root, const NodePool& nodes, const LargeArray<PrimRef>& refs,
                const Primitives& prims, ThreadPool& pool, BvhData& out, BuildSummary& summary);

}  // namespace glint::bvh::builder
