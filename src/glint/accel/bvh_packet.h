#pragma once
/// A ray packet prepared for traversal: the data every instruction set's packet kernels share
/// (see the packet section of bvh_traverse.inl for how it is traversed).

#include <algorithm>
#include <cstdint>
#include <limits>

#include "glint/core/ray.h"

namespace glint::bvh {

/// The active rays of a packet as single rays, and what interval traversal needs: the common
/// origin, per-axis bounds of the reciprocal directions, and which box plane is met first.
struct Packet {
    uint32_t active = 0;
    TraversalRay rays[8] = {};
    bool coherent = true;   ///< Common origin and per-axis direction signs.
    bool sameFrame = true;  ///< All rays share the watertight test's axes (kx, ky, kz).
    float origin[3] = {};
    float invLo[3] = {}, invHi[3] = {};
    bool nearHi[3] = {};
    float tMin = std::numeric_limits<float>::infinity();

    explicit Packet(const RayPacket8& p) : active(p.active) {
        int first = -1;
        for (int i = 0; i < 8; ++i) {
            if (!(active >> i & 1)) continue;
            rays[i] = p.ray(i);
            const TraversalRay& r = rays[i];
            if (first < 0) {
                first = i;
                for (int a = 0; a < 3; ++a) {
                    origin[a] = r.origin[a];
                    invLo[a] = invHi[a] = r.invDir[a];
                    nearHi[a] = r.invDir[a] < 0;
                }
            }
            const TraversalRay& f = rays[first];
            sameFrame = sameFrame && r.kz == f.kz;
            for (int a = 0; a < 3; ++a) {
                coherent = coherent && r.origin[a] == origin[a] && (r.invDir[a] < 0) == nearHi[a];
                invLo[a] = std::min(invLo[a], r.invDir[a]);
                invHi[a] = std::max(invHi[a], r.invDir[a]);
            }
            tMin = std::min(tMin, r.tMin);
        }
    }
};

}  // namespace glint::bvh
