// MikkTSpace-compatible tangents (tangents.h has the algorithm in words): per-triangle
// tangents and handedness, corners welded by value, groups of edge-connected triangles of one
// handedness around each vertex, and the angle-weighted sum of projected tangents per group.

#include "glint/scene/tangents.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "glint/core/error.h"
#include "glint/math/bits.h"
#include "glint/math/sampling.h"

namespace glint {
namespace {

constexpr uint32_t kNone = MeshData::kNone;

/// MikkTSpace's test for "not zero": above the smallest normal float, so that denormal areas
/// and lengths count as zero.
bool notZero(double x) { return std::abs(x) > double(std::numeric_limits<float>::min()); }

/// `v` without its component along the unit (or zero) vector `n`.
Vec3 project(const Vec3& v, const Vec3& n) { return v - n * dot(n, v); }

/// `v` normalised, or zero.
Vec3 unitOrZero(const Vec3& v) {
    double len = length(v);
    return notZero(len) ? v / len : Vec3(0);
}

/// A corner of a selected triangle: what welding compares. -0 is stored as +0, so that equal
/// values compare equal bit for bit.
struct CornerKey {
    std::array<float, 8> v;  // position, normal, uv

    Vec3 position() const { return {v[0], v[1], v[2]}; }
    Vec3 normal() const { return {v[3], v[4], v[5]}; }
    /// Whether the normal and uv are those of `o` (the position is compared apart).
    bool sameNormalAndUv(const CornerKey& o) const {
        return std::equal(v.begin() + 3, v.end(), o.v.begin() + 3);
    }
};

float canonical(float x) { return x + 0.0f; }

/// What is known of one selected triangle.
struct Tri {
    size_t index;               ///< In MeshData::triangles.
    std::array<uint32_t, 3> w;  ///< Welded vertex of each corner.
    Vec3f tangent;              ///< dp/du, normalised; zero when the uvs have no area.
    int8_t orientation = 0;     ///< +1, -1; 0: the uvs have no area (decided from neighbours).
    bool degenerate = false;    ///< Two equal corner positions (no area).
    std::array<uint32_t, 3> neighbour{kNone, kNone, kNone};  ///< Across edge k (corner k, k+1).
    std::array<uint32_t, 3> group{kNone, kNone, kNone};      ///< Of corner k.
};

/// A vertex's triangles that share edges and handedness.
struct Group {
    uint32_t vertex;  ///< Welded vertex.
    int orientation;
    Vec3 sum;          ///< Angle-weighted projected tangents.
    uint32_t tangent;  ///< Index in MeshData::tangents.
};

/// A selected triangle's corner positions and the normals its tangents are made for, from its
/// corner keys.
struct Corners {
    std::array<Vec3, 3> p, n;

    explicit Corners(const CornerKey* keys) {
        for (size_t k = 0; k < 3; ++k) {
            p[k] = keys[k].position();
            n[k] = keys[k].normal();
        }
    }
};

/// A unit vector orthogonal to `n` (any, if `n` is zero).
Vec3 anyTangent(const Vec3& n) {
    double len = length(n);
    if (!notZero(len)) return {1, 0, 0};
    return Frame(n / len).t;
}

/// Reads the selected triangles: corner keys (the vertex normals, else the face normal, zero
/// when the triangle has no area), the mesh position of each corner, per-triangle tangents and
/// handedness.
std::vector<Tri> readTriangles(const MeshData& mesh, const TangentRequest& request,
                               std::vector<CornerKey>& keys, std::vector<uint32_t>& positionOf) {
    const auto& uvs = request.secondUvs ? mesh.uv1s : mesh.uvs;
    const size_t last = std::min(request.last, mesh.triangles.size());
    std::vector<Tri> tris;
    if (request.first < last) {
        tris.reserve(last - request.first);
        keys.reserve(3 * (last - request.first));
        positionOf.reserve(3 * (last - request.first));
    }
    for (size_t i = request.first; i < last; ++i) {
        const MeshData::Triangle& t = mesh.triangles[i];
        const MeshData::Corner& c0 = t.corners[0];
        if ((request.secondUvs ? c0.uv1 : c0.uv) == kNone || c0.tangent != kNone) continue;
        if (request.select && !request.select(t)) continue;
        Tri tri;
        tri.index = i;
        std::array<TexCoord, 3> uv;
        for (size_t k = 0; k < 3; ++k) {
            const MeshData::Corner& c = t.corners[k];
            uv[k] = uvs[request.secondUvs ? c.uv1 : c.uv];
        }
        std::array<Vec3, 3> p, n;
        for (size_t k = 0; k < 3; ++k) p[k] = Vec3(mesh.positions[t.corners[k].position]);
        const Vec3 e1 = p[1] - p[0], e2 = p[2] - p[0];
        const Vec3 face = unitOrZero(cross(e1, e2));
        for (size_t k = 0; k < 3; ++k) {
            const uint32_t ni = t.corners[k].normal;
            const Vec3 vn = ni != kNone ? Vec3(mesh.normals[ni]) : Vec3(0);
            n[k] = notZero(length(vn)) ? vn : face;
        }
        tri.degenerate = p[0] == p[1] || p[1] == p[2] || p[0] == p[2];
        // dp/du and dp/dv from e1 = dp/du du1 + dp/dv dv1 and e2 likewise: times the uv area.
        const double du1 = double(uv[1][0]) - uv[0][0], dv1 = double(uv[1][1]) - uv[0][1];
        const double du2 = double(uv[2][0]) - uv[0][0], dv2 = double(uv[2][1]) - uv[0][1];
        const double area = du1 * dv2 - du2 * dv1;
        if (notZero(area)) {
            tri.orientation = area > 0 ? 1 : -1;
            tri.tangent = Vec3f(unitOrZero((e1 * dv2 - e2 * dv1) * double(tri.orientation)));
        }
        for (size_t k = 0; k < 3; ++k) {
            CornerKey key;
            key.v = {float(p[k].x), float(p[k].y), float(p[k].z), float(n[k].x),
                     float(n[k].y), float(n[k].z), uv[k][0],      uv[k][1]};
            for (float& x : key.v) x = canonical(x);
            keys.push_back(key);
            positionOf.push_back(t.corners[k].position);
        }
        tris.push_back(tri);
    }
    return tris;
}

/// A well-mixed 64-bit hash of `x` (the finaliser of MurmurHash3).
uint64_t mix(uint64_t x) {
    x ^= x >> 33;
    x *= 0xff51afd7ed558ccdULL;
    x ^= x >> 33;
    x *= 0xc4ceb9fe1a85ec53ULL;
    return x ^ (x >> 33);
}

/// Numbers the distinct corner keys, in the order they first occur: corners of equal position,
/// normal and uv are one vertex. Returns the number of vertices. Equal positions are found by
/// value once per mesh position (a hash table), then the few vertices at each position by
/// their normal and uv.
uint32_t weld(std::vector<Tri>& tris, const std::vector<CornerKey>& keys,
              const std::vector<uint32_t>& positionOf) {
    // Mesh position -> distinct position value (a place), for the range of mesh positions the
    // corners use (a glTF primitive's are contiguous).
    const auto [lo, hi] = std::minmax_element(positionOf.begin(), positionOf.end());
    const uint32_t first = *lo;
    std::vector<uint32_t> place(size_t(*hi - first) + 1, kNone);
    const size_t mask =
        std::bit_ceil(std::max<size_t>(2 * std::min(place.size(), keys.size()), 16)) - 1;
    std::vector<uint32_t> slots(mask + 1, kNone), slotPlace(mask + 1);
    // Each place's vertices: a list through `next`, each vertex known by one of its corners.
    std::vector<uint32_t> head, next, corner;
    for (uint32_t c = 0; c < keys.size(); ++c) {
        const CornerKey& key = keys[c];
        uint32_t& at = place[positionOf[c] - first];
        if (at == kNone) {
            uint64_t h = 0;
            for (size_t k = 0; k < 3; ++k) h = mix(h ^ bitCast<uint32_t>(key.v[k]));
            size_t i = h & mask;
            while (slots[i] != kNone &&
                   !std::equal(key.v.begin(), key.v.begin() + 3, keys[slots[i]].v.begin()))
                i = (i + 1) & mask;
            if (slots[i] == kNone) {
                slots[i] = c;
                slotPlace[i] = uint32_t(head.size());
                head.push_back(kNone);
            }
            at = slotPlace[i];
        }
        uint32_t v = head[at];
        while (v != kNone && !keys[corner[v]].sameNormalAndUv(key)) v = next[v];
        if (v == kNone) {
            v = uint32_t(corner.size());
            corner.push_back(c);
            next.push_back(head[at]);
            head[at] = v;
        }
        tris[c / 3].w[c % 3] = v;
    }
    return uint32_t(corner.size());
}

/// Links triangles across their edges: edge (a, b) of one and (b, a) of another (the same
/// winding; of several, the first). Degenerate triangles have no neighbours.
void linkNeighbours(std::vector<Tri>& tris, uint32_t vertices) {
    // The triangles at each vertex, in order.
    std::vector<uint32_t> start(size_t(vertices) + 1, 0), at;
    for (const Tri& t : tris)
        if (!t.degenerate)
            for (uint32_t v : t.w) ++start[v + 1];
    for (size_t v = 0; v < vertices; ++v) start[v + 1] += start[v];
    at.resize(start[vertices]);
    std::vector<uint32_t> fill(start.begin(), start.end() - 1);
    for (size_t t = 0; t < tris.size(); ++t)
        if (!tris[t].degenerate)
            for (uint32_t v : tris[t].w) at[fill[v]++] = uint32_t(t);
    for (size_t t = 0; t < tris.size(); ++t) {
        Tri& tri = tris[t];
        if (tri.degenerate) continue;
        for (size_t k = 0; k < 3; ++k) {
            const uint32_t a = tri.w[k], b = tri.w[(k + 1) % 3];
            for (uint32_t i = start[b]; i < start[b + 1] && tri.neighbour[k] == kNone; ++i) {
                const Tri& u = tris[at[i]];
                if (at[i] == t) continue;
                for (size_t j = 0; j < 3; ++j)
                    if (u.w[j] == b && u.w[(j + 1) % 3] == a) tri.neighbour[k] = at[i];
            }
        }
    }
}

/// Triangles whose uvs have no area take the handedness of a neighbour, spreading out from the
/// triangles that have one; those that reach none are +1.
void decideOrientations(std::vector<Tri>& tris) {
    std::vector<uint32_t> queue;
    for (size_t t = 0; t < tris.size(); ++t)
        if (tris[t].orientation != 0) queue.push_back(uint32_t(t));
    for (size_t q = 0; q < queue.size(); ++q) {
        const Tri& from = tris[queue[q]];
        for (uint32_t u : from.neighbour)
            if (u != kNone && tris[u].orientation == 0) {
                tris[u].orientation = from.orientation;
                queue.push_back(u);
            }
    }
    for (Tri& t : tris)
        if (t.orientation == 0) t.orientation = 1;
}

/// The corner of `tri` at welded vertex `v`, or 3.
size_t cornerAt(const Tri& tri, uint32_t v) {
    for (size_t k = 0; k < 3; ++k)
        if (tri.w[k] == v) return k;
    return 3;
}

/// Forms the groups: from each corner not yet grouped, the triangles reached around its vertex
/// through shared edges, as long as their handedness is the group's.
std::vector<Group> formGroups(std::vector<Tri>& tris) {
    std::vector<Group> groups;
    std::vector<std::pair<uint32_t, size_t>> stack;  // (triangle, corner)
    for (size_t t = 0; t < tris.size(); ++t) {
        if (tris[t].degenerate) continue;
        for (size_t k = 0; k < 3; ++k) {
            if (tris[t].group[k] != kNone) continue;
            const uint32_t g = uint32_t(groups.size());
            const uint32_t v = tris[t].w[k];
            groups.push_back({v, tris[t].orientation, Vec3(0), kNone});
            tris[t].group[k] = g;
            stack.assign(1, {uint32_t(t), k});
            while (!stack.empty()) {
                auto [ti, ci] = stack.back();
                stack.pop_back();
                // The two edges at corner ci: (ci, ci+1) and (ci+2, ci).
                for (size_t e : {ci, (ci + 2) % 3}) {
                    const uint32_t u = tris[ti].neighbour[e];
                    if (u == kNone) continue;
                    Tri& next = tris[u];
                    const size_t cj = cornerAt(next, v);
                    if (cj == 3 || next.group[cj] != kNone ||
                        next.orientation != groups[g].orientation)
                        continue;
                    next.group[cj] = g;
                    stack.push_back({u, cj});
                }
            }
        }
    }
    return groups;
}

/// The angle at corner `k`, between its edges projected onto the plane of `n`.
double cornerAngle(const Corners& g, size_t k, const Vec3& n) {
    const Vec3 a = unitOrZero(project(g.p[(k + 1) % 3] - g.p[k], n));
    const Vec3 b = unitOrZero(project(g.p[(k + 2) % 3] - g.p[k], n));
    return std::acos(std::clamp(dot(a, b), -1.0, 1.0));
}

}  // namespace

size_t tangentGenerationBytes(size_t triangles) {
    // Per triangle: its record; per corner, its key, at most one group, and a dozen indices
    // (its mesh position, the vertex lists, the triangles at each vertex, the hash table).
    return triangles *
           (sizeof(Tri) + 3 * (sizeof(CornerKey) + sizeof(Group) + 12 * sizeof(uint32_t)));
}

TangentReport generateTangents(MeshData& mesh, const TangentRequest& request) {
    std::vector<CornerKey> keys;
    std::vector<uint32_t> positionOf;
    std::vector<Tri> tris = readTriangles(mesh, request, keys, positionOf);
    TangentReport report;
    if (tris.empty()) return report;
    if (keys.size() >= kNone)
        throw SceneError({mesh.name, 0, 0},
                         "too many triangles to generate tangents for (more than 1.4 billion)");
    const uint32_t vertices = weld(tris, keys, positionOf);
    positionOf = {};
    linkNeighbours(tris, vertices);
    decideOrientations(tris);
    std::vector<Group> groups = formGroups(tris);

    // Each group's sum of its triangles' tangents, projected and weighted by angle.
    for (size_t i = 0; i < tris.size(); ++i) {
        const Tri& tri = tris[i];
        if (tri.degenerate || tri.tangent == Vec3f(0)) continue;
        const Corners g(&keys[3 * i]);
        for (size_t k = 0; k < 3; ++k) {
            const Vec3 t = unitOrZero(project(Vec3(tri.tangent), g.n[k]));
            if (t == Vec3(0)) continue;
            groups[tri.group[k]].sum += t * cornerAngle(g, k, g.n[k]);
        }
    }

    // One tangent per group, orthonormalised against the normal, which all its corners share.
    std::vector<uint32_t> firstGroupOf;  // by welded vertex
    auto add = [&](const Vec3& t, int sign) {
        if (mesh.tangents.size() >= kNone)
            throw SceneError({mesh.name, 0, 0}, "the mesh has more than 4 billion tangents");
        mesh.tangents.push_back({float(t.x), float(t.y), float(t.z), sign < 0 ? -1.0f : 1.0f});
        ++report.tangents;
        return uint32_t(mesh.tangents.size() - 1);
    };
    auto tangentOf = [&](Group& g, const Vec3& n) {
        if (g.tangent != kNone) return g.tangent;
        Vec3 t = unitOrZero(project(g.sum, n));
        if (t == Vec3(0)) {
            t = anyTangent(n);
            ++report.fallback;
        }
        g.tangent = add(t, g.orientation);
        if (firstGroupOf.size() <= g.vertex) firstGroupOf.resize(g.vertex + 1, kNone);
        if (firstGroupOf[g.vertex] == kNone) firstGroupOf[g.vertex] = g.tangent;
        return g.tangent;
    };
    for (size_t i = 0; i < tris.size(); ++i) {
        const Tri& tri = tris[i];
        if (tri.degenerate) continue;
        auto& corners = mesh.triangles[tri.index].corners;
        for (size_t k = 0; k < 3; ++k)
            corners[k].tangent = tangentOf(groups[tri.group[k]], keys[3 * i + k].normal());
        ++report.triangles;
    }
    // Corners of degenerate triangles: another group's tangent at the same vertex, else any.
    for (size_t i = 0; i < tris.size(); ++i) {
        const Tri& tri = tris[i];
        if (!tri.degenerate) continue;
        const Corners g(&keys[3 * i]);
        auto& corners = mesh.triangles[tri.index].corners;
        for (size_t k = 0; k < 3; ++k) {
            const uint32_t v = tri.w[k];
            if (v < firstGroupOf.size() && firstGroupOf[v] != kNone) {
                corners[k].tangent = firstGroupOf[v];
            } else {
                corners[k].tangent = add(anyTangent(g.n[k]), tri.orientation);
                ++report.fallback;
            }
        }
        ++report.triangles;
    }
    return report;
}

}  // namespace glint
