#pragma once
/// A ray packet prepared for traversal: the data every instruction set's packet kernels share
/// (see the packet section of bvh_traverse.inl for how it is traversed).

#include <algorithm>
#include <cstdint>
#include <limits>

#include "glint/core/ray.h"

namespace glint::bvh {

/// The active rays of a packet, and what interval traversal needs. Per axis, when all rays run
/// the same way, a ray's entry distance (plane - o) * inv into a slab is monotonic in its
/// origin o: the nearest possible entry over the packet uses the origin bound on one side
/// (`originNear`), the farthest possible exit the other (`originFar`); with the interval
/// [invLo, invHi] of reciprocal directions that bounds every ray's own slab distances.
struct Packet {
    uint32_t active = 0;
    const TraversalRay* rays;  ///< The packet's rays, read in place.
    bool coherent = true;      ///< On every axis, all rays run the same way.
    bool sameFrame = true;     ///< All rays share the watertight test's axes (kx, ky, kz).
    float originNear[3] = {}, originFar[3] = {};
    float invLo[3] = {}, invHi[3] = {};
    bool nearHi[3] = {};  ///< The ray enters a box through `hi` on this axis.
    float tMin = std::numeric_limits<float>::infinity();

    explicit Packet(const RayPacket8& p) : active(p.active), rays(p.rays) {
        float oLo[3], oHi[3];
        int first = -1;
        for (int i = 0; i < 8; ++i) {
            if (!(active >> i & 1)) continue;
            const TraversalRay& r = rays[i];
            if (first < 0) {
                first = i;
                for (int a = 0; a < 3; ++a) {
                    oLo[a] = oHi[a] = r.origin[a];
                    invLo[a] = invHi[a] = r.invDir[a];
                    nearHi[a] = r.invDir[a] < 0;
                }
            }
            sameFrame = sameFrame && r.kz == rays[first].kz;
            for (int a = 0; a < 3; ++a) {
                coherent = coherent && (r.invDir[a] < 0) == nearHi[a];
                oLo[a] = std::min(oLo[a], r.origin[a]);
                oHi[a] = std::max(oHi[a], r.origin[a]);
                invLo[a] = std::min(invLo[a], r.invDir[a]);
                invHi[a] = std::max(invHi[a], r.invDir[a]);
            }
            tMin = std::min(tMin, r.tMin);
        }
        if (first < 0) return;
        for (int a = 0; a < 3; ++a) {
            originNear[a] = nearHi[a] ? oLo[a] : oHi[a];
            originFar[a] = nearHi[a] ? oHi[a] : oLo[a];
        }
    }
};

}  // namespace glint::bvh
