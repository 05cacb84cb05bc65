// The portable traversal kernels: plain C++ loops, compiled for the baseline instruction set.

#include <algorithm>
#include <bit>
#include <limits>

#include "glint/accel/bvh_build.h"
#include "glint/accel/bvh_kernels.h"
#include "glint/accel/bvh_packet.h"
#include "glint/geometry/shapes.h"
#include "glint/geometry/sphere.h"
#include "glint/geometry/triangle.h"

namespace glint::bvh::portable {
namespace {

struct Isa {
    struct RayBoxes {
        Vec3f origin, invDir;
        float tMin;
        bool negative[3];

        explicit RayBoxes(const TraversalRay& r)
            : origin(r.origin),
              invDir(r.invDir),
              tMin(r.tMin),
              negative{r.invDir.x < 0, r.invDir.y < 0, r.invDir.z < 0} {}
    };

    static uint32_t boxes(const Node8& n, const RayBoxes& r, float tMax, float* tNear) {
        constexpr float farScale = 1 + 4 * std::numeric_limits<float>::epsilon();
        uint32_t mask = 0;
        for (int i = 0; i < kWidth; ++i) {
            float enter = r.tMin, exit = std::numeric_limits<float>::infinity();
            for (int a = 0; a < 3; ++a) {
                float nearPlane = r.negative[a] ? n.hi[a][i] : n.lo[a][i];
                float farPlane = r.negative[a] ? n.lo[a][i] : n.hi[a][i];
                enter = std::max(enter, (nearPlane - r.origin[a]) * r.invDir[a]);
                exit = std::min(exit, (farPlane - r.origin[a]) * r.invDir[a]);
            }
            exit = std::min(exit * farScale, tMax);
            tNear[i] = enter;
            mask |= static_cast<uint32_t>(enter <= exit) << i;
        }
        return mask;
    }

    static uint32_t triangles(const Tri4& b, const TraversalRay& ray, float tBest, float* t) {
        uint32_t mask = 0;
        for (int lane = 0; lane < kLanes; ++lane) {
            Triangle tri{{b.v0[0][lane], b.v0[1][lane], b.v0[2][lane]},
                         {b.v1[0][lane], b.v1[1][lane], b.v1[2][lane]},
                         {b.v2[0][lane], b.v2[1][lane], b.v2[2][lane]}};
            if (intersectTriangle(tri, ray, t[lane]) && t[lane] <= tBest) mask |= 1u << lane;
        }
        return mask;
    }

    // Packets (see bvh_traverse.inl): plain loops over the eight rays.
    struct PacketBoxes {
        const Packet* p;
        explicit PacketBoxes(const Packet& packet) : p(&packet) {}
    };
    struct PacketLanes {
        const Packet* p;
        explicit PacketLanes(const Packet& packet) : p(&packet) {}
    };

    static uint32_t packetBoxes(const Node8& n, const PacketBoxes& b, float tMax, float* tNear) {
        constexpr float farScale = 1 + 4 * std::numeric_limits<float>::epsilon();
        const Packet& p = *b.p;
        uint32_t mask = 0;
        for (int i = 0; i < kWidth; ++i) {
            float enter = p.tMin, exit = std::numeric_limits<float>::infinity();
            for (int a = 0; a < 3; ++a) {
                float dn = (p.nearHi[a] ? n.hi[a][i] : n.lo[a][i]) - p.originNear[a];
                float df = (p.nearHi[a] ? n.lo[a][i] : n.hi[a][i]) - p.originFar[a];
                enter = std::max(enter, std::min(dn * p.invLo[a], dn * p.invHi[a]));
                exit = std::min(exit, std::max(df * p.invLo[a], df * p.invHi[a]));
            }
            exit = std::min(exit * farScale, tMax);
            tNear[i] = enter;
            mask |= static_cast<uint32_t>(enter <= exit) << i;
        }
        return mask;
    }

    static void packetTriangles(const Tri4& b, const PacketLanes& l, float* bestT,
                                uint32_t* bestId) {
        for (int lane = 0; lane < 8; ++lane) {
            if (!(l.p->active >> lane & 1)) continue;
            Hit hit{bestT[lane], bestId[lane]};
            alignas(16) float t[kLanes];
            uint32_t hits = triangles(b, l.p->rays[lane], hit.t, t);
            while (hits) {
                int k = std::countr_zero(hits);
                hits &= hits - 1;
                if (closerHit(t[k], b.id[k], hit)) hit = {t[k], b.id[k]};
            }
            bestT[lane] = hit.t, bestId[lane] = hit.primId;
        }
    }
};

#include "glint/accel/bvh_traverse.inl"

}  // namespace

bool intersect(const BvhData& d, const TraversalRay& ray, Hit& hit) {
    return traverse<false>(d, ray, hit);
}

bool occluded(const BvhData& d, const TraversalRay& ray) {
    Hit hit;
    return traverse<true>(d, ray, hit);
}

void intersect8(const BvhData& d, const RayPacket8& rays, HitPacket8& hits) {
    traversePacket(d, rays, hits);
}

}  // namespace glint::bvh::portable
