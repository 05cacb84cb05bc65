#include "glint/geometry/deforming_mesh.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>

namespace glint {
namespace {

constexpr uint32_t kLeafSize = 4;
constexpr int kMaxDepth = 64;  ///< Median splits halve: 64 levels hold any mesh.

}  // namespace

DeformingMesh::DeformingMesh(std::vector<std::vector<Corners>> vertices,
                             std::vector<std::vector<Corners>> normals) {
    if (vertices.size() < 2) throw std::invalid_argument("a deforming mesh needs two keys");
    keys_ = static_cast<int>(vertices.size());
    count_ = static_cast<uint32_t>(vertices.front().size());
    if (!normals.empty() && normals.size() != vertices.size())
        throw std::invalid_argument("a deforming mesh needs normals at every key or none");
    for (size_t k = 0; k < vertices.size(); ++k) {
        if (vertices[k].size() != count_ || (!normals.empty() && normals[k].size() != count_))
            throw std::invalid_argument("a deforming mesh's keys differ in size");
        vertices_.insert(vertices_.end(), vertices[k].begin(), vertices[k].end());
        if (!normals.empty()) normals_.insert(normals_.end(), normals[k].begin(), normals[k].end());
    }
    if (count_ == 0) return;
    std::vector<Bounds3f> boxes(count_);
    for (int k = 0; k < keys_; ++k)
        for (uint32_t i = 0; i < count_; ++i)
            for (const Vec3f& v : vertices_[static_cast<size_t>(k) * count_ + i])
                boxes[i].extend(v);
    order_.resize(count_);
    std::iota(order_.begin(), order_.end(), 0u);
    nodes_.reserve(2 * (count_ / kLeafSize + 1));
    build(0, count_, boxes, 0);
}

uint32_t DeformingMesh::build(uint32_t begin, uint32_t end, const std::vector<Bounds3f>& boxes,
                              int depth) {
    const auto index = static_cast<uint32_t>(nodes_.size());
    nodes_.emplace_back();
    Bounds3f box, centres;
    for (uint32_t i = begin; i < end; ++i) {
        const Bounds3f& b = boxes[order_[i]];
        box.extend(b.lo);
        box.extend(b.hi);
        centres.extend((b.lo + b.hi) * 0.5f);
    }
    nodes_[index].box = box;
    const Vec3f extent = centres.hi - centres.lo;
    const int axis =
        extent.x >= extent.y ? (extent.x >= extent.z ? 0 : 2) : (extent.y >= extent.z ? 1 : 2);
    if (end - begin <= kLeafSize || depth + 1 >= kMaxDepth || !(extent[axis] > 0)) {
        nodes_[index].first = begin;
        nodes_[index].count = end - begin;
        return index;
    }
    // The median along the widest axis of the centres; ties by index, so the tree is the same
    // on every machine.
    const uint32_t mid = begin + (end - begin) / 2;
    std::nth_element(order_.begin() + begin, order_.begin() + mid, order_.begin() + end,
                     [&](uint32_t a, uint32_t b) {
                         const float ca = boxes[a].lo[axis] + boxes[a].hi[axis];
                         const float cb = boxes[b].lo[axis] + boxes[b].hi[axis];
                         return ca < cb || (ca == cb && a < b);
                     });
    build(begin, mid, boxes, depth + 1);
    const uint32_t second = build(mid, end, boxes, depth + 1);
    nodes_[index].first = second;
    return index;
}

DeformingMesh::Corners DeformingMesh::lerp(const std::vector<Corners>& keyed, uint32_t i,
                                           float u) const {
    const float s = std::clamp(u, 0.0f, 1.0f) * static_cast<float>(keys_ - 1);
    const int k = std::min(static_cast<int>(s), keys_ - 2);
    const float f = s - static_cast<float>(k);
    const Corners& a = keyed[static_cast<size_t>(k) * count_ + i];
    if (f == 0) return a;
    const Corners& b = keyed[static_cast<size_t>(k + 1) * count_ + i];
    Corners c;
    for (int j = 0; j < 3; ++j) c[j] = a[j] * (1 - f) + b[j] * f;
    return c;
}

template <bool kAnyHit>
bool DeformingMesh::search(const TraversalRay& ray, float u, Hit& hit) const {
    if (nodes_.empty()) return false;
    uint32_t stack[kMaxDepth];
    int top = 0;
    uint32_t node = 0;
    bool found = false;
    const auto best = [&] { return kAnyHit ? ray.tMax : std::min(ray.tMax, hit.t); };
    if (boxEntry(nodes_[0].box, ray, best()) == std::numeric_limits<float>::infinity())
        return false;
    for (;;) {
        const Node& n = nodes_[node];
        if (n.count > 0) {
            for (uint32_t j = n.first; j < n.first + n.count; ++j) {
                const uint32_t tri = order_[j];
                float t;
                if (!intersectTriangle(at(tri, u), ray, t)) continue;
                if (kAnyHit) return true;
                if (closerHit(t, tri, hit)) hit = {t, tri}, found = true;
            }
        } else {
            // Both children: the nearer first, the other kept for later.
            const uint32_t a = node + 1, b = n.first;
            const float ta = boxEntry(nodes_[a].box, ray, best());
            const float tb = boxEntry(nodes_[b].box, ray, best());
            constexpr float kMiss = std::numeric_limits<float>::infinity();
            if (ta != kMiss && tb != kMiss) {
                node = ta <= tb ? a : b;
                stack[top++] = ta <= tb ? b : a;
                continue;
            }
            if (ta != kMiss || tb != kMiss) {
                node = ta != kMiss ? a : b;
                continue;
            }
        }
        // Next from the stack, skipping boxes the best hit so far has passed.
        do {
            if (top == 0) return found;
            node = stack[--top];
        } while (!kAnyHit &&
                 boxEntry(nodes_[node].box, ray, best()) == std::numeric_limits<float>::infinity());
    }
}

bool DeformingMesh::intersect(const TraversalRay& ray, float u, Hit& hit) const {
    return search<false>(ray, u, hit);
}

bool DeformingMesh::occluded(const TraversalRay& ray, float u) const {
    Hit unused;
    return search<true>(ray, u, unused);
}

}  // namespace glint
