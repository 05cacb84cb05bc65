// Generic BVH traversal, instantiated once per instruction set (bvh_isa_*.cpp).
//
// Included inside a namespace that defines `struct Isa` with
//   struct Isa::RayBoxes { explicit RayBoxes(const TraversalRay&); };
//   static uint32_t Isa::boxes(const Node8&, const RayBoxes&, float tMax, float* tNear);
//     -> bit i set when child i's box meets [tMin, tMax] (conservatively); tNear[i] its entry;
//   static uint32_t Isa::triangles(const Tri4&, const TraversalRay&, float tBest, float* t);
//     -> bit i set when lane i is hit with tMin < t < tMax and t <= tBest, computing t exactly
//        as intersectTriangle() does;
// and nothing else: everything here is ISA-independent (shapes are tested by the scalar
// intersectShape() / intersectSphere(), the same code for every set). This file has no includes:
// the including file provides them before opening its namespace.

/// Widening of far distances and of the current best distance, so that rounding never culls
/// a box holding a hit at (or tied with) the best one.
constexpr float kFarScale = 1 + 4 * std::numeric_limits<float>::epsilon();

struct StackEntry {
    NodeRef ref;
    float dist;
};
constexpr int kStackSize = 7 * static_cast<int>(kMaxDepth) + 1;

template <bool AnyHit>
bool traverse(const BvhData& d, const TraversalRay& ray, Hit& hit);

/// Instance record `i`: the ray mapped into the mesh's space (its direction not renormalised,
/// so t is the same) searches the mesh's tree. Closest hit: updates `hit` by the closerHit
/// rule with the instance's id, the mesh's primitive in subId.
template <bool AnyHit>
bool instanceHits(const BvhData& d, uint32_t i, const TraversalRay& ray, Hit& hit) {
    const ShapeSearch& s = d.shapes[i];
    Vec3f o, dir;
    s.map(ray, o, dir);
    // Up to and including the best hit so far: a tie goes to the lower id (closerHit below).
    float tMax = hit.t < ray.tMax ? std::nextafter(hit.t, ray.tMax) : ray.tMax;
    Hit sub;
    if (!traverse<AnyHit>(*d.meshes[s.mesh()], TraversalRay(o, dir, ray.tMin, tMax), sub))
        return false;
    if constexpr (AnyHit) return true;
    if (!closerHit(sub.t, d.shapeIds[i], hit)) return false;
    hit = {sub.t, d.shapeIds[i], sub.primId};
    return true;
}

/// A leaf of shapes that are not all spheres: each record is tested by its kind. Out of line
/// and cold, so that the sphere and triangle paths of the traversal loop keep their registers
/// (measured: inlined, or as a plain call, it cost sphere scenes 1-2% more instructions).
template <bool AnyHit>
[[gnu::noinline, gnu::cold]] bool shapeRunHits(const BvhData& d, ShapeRun run,
                                               const TraversalRay& ray, Hit& hit) {
    bool found = false;
    for (uint32_t i = run.first; i < run.first + run.count; ++i) {
        if (d.shapes[i].kind == ShapeKind::Instance) {
            if (!instanceHits<AnyHit>(d, i, ray, hit)) continue;
            if constexpr (AnyHit) return true;
            found = true;
            continue;
        }
        float t;
        if (!intersectShape(d.shapes[i], ray, t)) continue;
        if constexpr (AnyHit) return true;
        if (closerHit(t, d.shapeIds[i], hit)) hit = {t, d.shapeIds[i]}, found = true;
    }
    return found;
}

/// Tests a leaf. Closest hit: updates `hit` by the closerHit rule. Any hit: returns true at the
/// first hit within the ray's range.
template <bool AnyHit>
inline bool leafHits(const BvhData& d, NodeRef ref, const TraversalRay& ray, Hit& hit) {
    uint32_t first = leafFirst(ref), count = leafCount(ref);
    bool found = false;
    if (isSphereLeaf(ref)) {
        for (uint32_t i = first; i < first + count; ++i) {
            float t;
            if (!intersectSphere(d.shapes[i], ray, t)) continue;
            if constexpr (AnyHit) return true;
            if (closerHit(t, d.shapeIds[i], hit)) hit = {t, d.shapeIds[i]}, found = true;
        }
        return found;
    }
    if (count == 0) return shapeRunHits<AnyHit>(d, d.shapeRuns[first], ray, hit);
    for (uint32_t b = first; b < first + count; ++b) {
        alignas(16) float t[kLanes];
        uint32_t lanes = Isa::triangles(d.tris[b], ray, hit.t, t);
        if constexpr (AnyHit) {
            if (lanes) return true;
        }
        while (lanes) {
            int lane = std::countr_zero(lanes);
            lanes &= lanes - 1;
            uint32_t id = d.tris[b].id[lane];
            if (closerHit(t[lane], id, hit)) hit = {t[lane], id}, found = true;
        }
    }
    return found;
}

/// At least two children were hit (`first` and the bits of `rest`): pushes all but the nearest,
/// farthest deepest, and returns the nearest. The common case of two is handled directly; more
/// are pushed and the pushed run sorted in place.
inline NodeRef orderChildren(const Node8& n, int first, uint32_t rest, const float* dist,
                             StackEntry* stack, int& sp) {
    int second = std::countr_zero(rest);
    rest &= rest - 1;
    if (rest == 0) {
        bool firstNearer = dist[first] <= dist[second];
        int nearC = firstNearer ? first : second, farC = firstNearer ? second : first;
        stack[sp++] = {n.child[farC], dist[farC]};
        return n.child[nearC];
    }
    int base = sp;
    stack[sp++] = {n.child[first], dist[first]};
    stack[sp++] = {n.child[second], dist[second]};
    while (rest) {
        int c = std::countr_zero(rest);
        rest &= rest - 1;
        stack[sp++] = {n.child[c], dist[c]};
    }
    // Descending by distance, so that the nearest is on top.
    for (int i = base + 1; i < sp; ++i) {
        StackEntry e = stack[i];
        int j = i;
        while (j > base && stack[j - 1].dist < e.dist) {
            stack[j] = stack[j - 1];
            --j;
        }
        stack[j] = e;
    }
    return stack[--sp].ref;
}

/// Closest hit (ordered, near child first, culling by distance) or any hit.
template <bool AnyHit>
bool traverse(const BvhData& d, const TraversalRay& ray, Hit& hit) {
    if (d.root == kEmpty) return false;
    const typename Isa::RayBoxes boxes(ray);
    StackEntry stack[kStackSize];
    int sp = 0;
    NodeRef ref = d.root;
    bool found = false;
    float limit = std::min(ray.tMax, hit.t) * kFarScale;
    for (;;) {
        // Descend to a leaf, pushing the other children met on the way.
        bool reachedLeaf = true;
        while (!isLeaf(ref)) {
            const Node8& n = d.nodes[ref];
            alignas(32) float dist[kWidth];
            uint32_t mask = Isa::boxes(n, boxes, limit, dist);
            if (mask == 0) {
                reachedLeaf = false;
                break;
            }
            int first = std::countr_zero(mask);
            mask &= mask - 1;
            if (mask == 0) {
                ref = n.child[first];
                continue;
            }
            if constexpr (AnyHit) {
                while (mask) {
                    int c = std::countr_zero(mask);
                    mask &= mask - 1;
                    stack[sp++] = {n.child[c], dist[c]};
                }
                ref = n.child[first];
                continue;
            }
            ref = orderChildren(n, first, mask, dist, stack, sp);
        }
        if (reachedLeaf && leafHits<AnyHit>(d, ref, ray, hit)) {
            if constexpr (AnyHit) return true;
            found = true;
            limit = std::min(ray.tMax, hit.t) * kFarScale;
        }
        // Pop the next subtree that can still hold a hit.
        for (;;) {
            if (sp == 0) return found;
            const StackEntry& e = stack[--sp];
            if (AnyHit || e.dist <= limit) {
                ref = e.ref;
                break;
            }
        }
    }
}

// ---- Packets ----------------------------------------------------------------------------
//
// A packet whose active rays share one origin and, per axis, one direction sign is traversed
// as a whole with interval arithmetic: per axis, the reciprocal directions lie in [lo, hi], so
// the nearest possible entry and farthest possible exit of a box over all the rays bound every
// ray's own. A box is culled only if no ray of the packet can meet it. At the leaves each
// triangle is tested against every ray with the arithmetic of intersectTriangle(), and each
// lane keeps its best hit by the closerHit rule: results equal single-ray traversal exactly.
// Other packets are traced one ray at a time.

/// The packet-level distance limit: the farthest any active ray still needs to look.
inline float packetLimit(const Packet& p, const float* bestT) {
    float limit = 0;
    for (int i = 0; i < 8; ++i)
        if (p.active >> i & 1) limit = std::max(limit, std::min(p.rays[i].tMax, bestT[i]));
    return limit * kFarScale;
}

/// The spheres of a sphere leaf against every active ray of a packet.
inline void packetSpheres(const BvhData& d, uint32_t first, uint32_t count, const Packet& p,
                          float* bestT, uint32_t* bestId) {
    for (uint32_t i = first; i < first + count; ++i)
        for (int lane = 0; lane < 8; ++lane) {
            float t;
            if (!(p.active >> lane & 1) || !intersectSphere(d.shapes[i], p.rays[lane], t)) continue;
            Hit best{bestT[lane], bestId[lane]};
            if (closerHit(t, d.shapeIds[i], best)) bestT[lane] = t, bestId[lane] = d.shapeIds[i];
        }
}

/// The shapes of a shape run against every active ray of a packet, each by its kind. Out of
/// line and cold, like shapeRunHits. An instance hit sets the lane's subId (read only while
/// the lane's best id is that instance).
[[gnu::noinline, gnu::cold]] void packetShapeRun(const BvhData& d, ShapeRun run, const Packet& p,
                                                 float* bestT, uint32_t* bestId,
                                                 uint32_t* subId) {
    for (uint32_t i = run.first; i < run.first + run.count; ++i)
        for (int lane = 0; lane < 8; ++lane) {
            if (d.shapes[i].kind == ShapeKind::Instance) {
                Hit best{bestT[lane], bestId[lane], subId[lane]};
                if ((p.active >> lane & 1) && instanceHits<false>(d, i, p.rays[lane], best))
                    bestT[lane] = best.t, bestId[lane] = best.primId, subId[lane] = best.subId;
                continue;
            }
            float t;
            if (!(p.active >> lane & 1) || !intersectShape(d.shapes[i], p.rays[lane], t)) continue;
            Hit best{bestT[lane], bestId[lane]};
            if (closerHit(t, d.shapeIds[i], best)) bestT[lane] = t, bestId[lane] = d.shapeIds[i];
        }
}

inline void packetLeaf(const BvhData& d, NodeRef ref, const Packet& p,
                       const typename Isa::PacketLanes& lanes, float* bestT, uint32_t* bestId,
                       uint32_t* subId) {
    uint32_t first = leafFirst(ref), count = leafCount(ref);
    if (isSphereLeaf(ref)) return packetSpheres(d, first, count, p, bestT, bestId);
    if (count == 0) return packetShapeRun(d, d.shapeRuns[first], p, bestT, bestId, subId);
    for (uint32_t b = first; b < first + count; ++b) {
        if (p.sameFrame) {
            Isa::packetTriangles(d.tris[b], lanes, bestT, bestId);
            continue;
        }
        for (int lane = 0; lane < 8; ++lane) {
            if (!(p.active >> lane & 1)) continue;
            Hit hit{bestT[lane], bestId[lane]};
            alignas(16) float t[kLanes];
            uint32_t hits = Isa::triangles(d.tris[b], p.rays[lane], hit.t, t);
            while (hits) {
                int k = std::countr_zero(hits);
                hits &= hits - 1;
                if (closerHit(t[k], d.tris[b].id[k], hit)) hit = {t[k], d.tris[b].id[k]};
            }
            bestT[lane] = hit.t, bestId[lane] = hit.primId;
        }
    }
}

inline void traversePacket(const BvhData& d, const RayPacket8& rays, HitPacket8& hits) {
    if (d.root == kEmpty || rays.active == 0) return;
    const Packet p(rays);
    if (!p.coherent) {
        for (int i = 0; i < 8; ++i) {
            if (!(p.active >> i & 1)) continue;
            Hit h = hits[i];
            if (traverse<false>(d, p.rays[i], h)) hits.set(i, h);
        }
        return;
    }
    const typename Isa::PacketBoxes boxes(p);
    const typename Isa::PacketLanes lanes(p);
    alignas(32) float bestT[8];
    alignas(32) uint32_t bestId[8];
    for (int i = 0; i < 8; ++i) bestT[i] = hits.t[i], bestId[i] = hits.primId[i];

    StackEntry stack[kStackSize];
    int sp = 0;
    NodeRef ref = d.root;
    float limit = packetLimit(p, bestT);
    for (;;) {
        bool reachedLeaf = true;
        while (!isLeaf(ref)) {
            const Node8& n = d.nodes[ref];
            alignas(32) float dist[kWidth];
            uint32_t mask = Isa::packetBoxes(n, boxes, limit, dist);
            if (mask == 0) {
                reachedLeaf = false;
                break;
            }
            int first = std::countr_zero(mask);
            mask &= mask - 1;
            if (mask == 0) {
                ref = n.child[first];
                continue;
            }
            ref = orderChildren(n, first, mask, dist, stack, sp);
        }
        if (reachedLeaf) {
            packetLeaf(d, ref, p, lanes, bestT, bestId, hits.subId);
            limit = packetLimit(p, bestT);
        }
        for (;;) {
            if (sp == 0) {
                for (int i = 0; i < 8; ++i)
                    if (p.active >> i & 1) hits.t[i] = bestT[i], hits.primId[i] = bestId[i];
                return;
            }
            const StackEntry& e = stack[--sp];
            if (e.dist <= limit) {
                ref = e.ref;
                break;
            }
        }
    }
}
