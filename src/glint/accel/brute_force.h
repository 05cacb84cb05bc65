#pragma once
/// Tests every primitive: the oracle that the BVH is checked against.

#include "glint/geometry/primitives.h"

namespace glint {

class BruteForce {
  public:
    /// Keeps a reference: `prims` must outlive this accelerator.
    void build(const Primitives& prims) { prims_ = &prims; }

    bool intersect(const Ray& ray, Hit& hit) const {
        TraversalRay r(ray);
        bool found = false;
        for (uint32_t i = 0; i < prims_->size(); ++i) found |= prims_->intersect(i, r, hit);
        return found;
    }
    bool occluded(const Ray& ray) const {
        TraversalRay r(ray);
        Hit hit;
        for (uint32_t i = 0; i < prims_->size(); ++i)
            if (prims_->intersect(i, r, hit)) return true;
        return false;
    }

  private:
    const Primitives* prims_ = nullptr;
};

}  // namespace glint
