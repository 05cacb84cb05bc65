// MikkTSpace-compatible tangents (tangents.h has the algorithm in words): per-triangle
// tangents and handedness, corners welded by value, groups of edge-connected triangles of one
// handedness around each vertex, and the angle-weighted sum of projected tangents per group.

#include "glint/scene/tangents.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <vector>

#include "glint/core/error.h"
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

    auto operator<=>(const CornerKey&) const = default;
};

float canonical(float x) { return x + 0.0f; }

/// What is known of one selected triangle.
struct Tri {
    size_t index;               ///< In MeshData::triangles.
    std::array<uint32_t, 3> w;  ///< Welded vertex of each corner.
    Vec3 tangent;               ///< dp/du, normalised; zero when the uvs have no area.
    int orientation = 0;        ///< +1, -1; 0: the uvs have no area (decided from neighbours).
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

/// A triangle's corner positions and the normals its tangents are made for: the vertex normals,
/// else its face normal (zero when it has no area).
struct Corners {
    std::array<Vec3, 3> p, n;

    Corners(const MeshData& mesh, const MeshData::Triangle& t) {
        for (size_t k = 0; k < 3; ++k) p[k] = Vec3(mesh.positions[t.corners[k].position]);
        const Vec3 face = unitOrZero(cross(p[1] - p[0], p[2] - p[0]));
        for (size_t k = 0; k < 3; ++k) {
            const uint32_t i = t.corners[k].normal;
            const Vec3 vn = i != kNone ? Vec3(mesh.normals[i]) : Vec3(0);
            n[k] = notZero(length(vn)) ? vn : face;
        }
    }
};

/// A unit vector orthogonal to `n` (any, if `n` is zero).
Vec3 anyTangent(const Vec3& n) {
    double len = length(n);
    if (!notZero(len)) return {1, 0, 0};
    return Frame(n / len).t;
}

/// Reads the selected triangles: corners, per-triangle tangents and handedness.
std::vector<Tri> readTriangles(const MeshData& mesh, const TangentRequest& request,
                               std::vector<CornerKey>& keys) {
    const auto& uvs = request.secondUvs ? mesh.uv1s : mesh.uvs;
    const size_t last = std::min(request.last, mesh.triangles.size());
    std::vector<Tri> tris;
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
        const Corners g(mesh, t);
        const Vec3 e1 = g.p[1] - g.p[0], e2 = g.p[2] - g.p[0];
        tri.degenerate = g.p[0] == g.p[1] || g.p[1] == g.p[2] || g.p[0] == g.p[2];
        // dp/du and dp/dv from e1 = dp/du du1 + dp/dv dv1 and e2 likewise: times the uv area.
        const double du1 = double(uv[1][0]) - uv[0][0], dv1 = double(uv[1][1]) - uv[0][1];
        const double du2 = double(uv[2][0]) - uv[0][0], dv2 = double(uv[2][1]) - uv[0][1];
        const double area = du1 * dv2 - du2 * dv1;
        if (notZero(area)) {
            tri.orientation = area > 0 ? 1 : -1;
            tri.tangent = unitOrZero((e1 * dv2 - e2 * dv1) * double(tri.orientation));
        }
        for (size_t k = 0; k < 3; ++k) {
            CornerKey key;
            key.v = {float(g.p[k].x), float(g.p[k].y), float(g.p[k].z), float(g.n[k].x),
                     float(g.n[k].y), float(g.n[k].z), uv[k][0],        uv[k][1]};
            for (float& x : key.v) x = canonical(x);
            keys.push_back(key);
        }
        tris.push_back(tri);
    }
    return tris;
}

/// Numbers the distinct corner keys: corners of equal position, normal and uv are one vertex.
void weld(std::vector<Tri>& tris, const std::vector<CornerKey>& keys) {
    std::vector<uint32_t> order(keys.size());
    std::iota(order.begin(), order.end(), 0u);
    std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
        return keys[a] < keys[b] || (keys[a] == keys[b] && a < b);
    });
    uint32_t vertex = 0;
    for (size_t i = 0; i < order.size(); ++i) {
        if (i > 0 && keys[order[i]] != keys[order[i - 1]]) ++vertex;
        tris[order[i] / 3].w[order[i] % 3] = vertex;
    }
}

/// Links triangles across their edges: edge (a, b) of one and (b, a) of another (the same
/// winding). Degenerate triangles have no neighbours.
void linkNeighbours(std::vector<Tri>& tris) {
    struct Edge {
        uint32_t a, b, tri, k;
    };
    std::vector<Edge> edges;
    edges.reserve(tris.size() * 3);
    for (size_t t = 0; t < tris.size(); ++t) {
        if (tris[t].degenerate) continue;
        for (uint32_t k = 0; k < 3; ++k)
            edges.push_back({tris[t].w[k], tris[t].w[(k + 1) % 3], uint32_t(t), k});
    }
    auto less = [](const Edge& x, const Edge& y) {
        return x.a != y.a ? x.a < y.a : x.b != y.b ? x.b < y.b : x.tri < y.tri;
    };
    std::sort(edges.begin(), edges.end(), less);
    for (const Edge& e : edges) {
        auto it = std::lower_bound(edges.begin(), edges.end(), Edge{e.b, e.a, 0, 0}, less);
        for (; it != edges.end() && it->a == e.b && it->b == e.a; ++it)
            if (it->tri != e.tri) {
                tris[e.tri].neighbour[e.k] = it->tri;
                break;
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

TangentReport generateTangents(MeshData& mesh, const TangentRequest& request) {
    std::vector<CornerKey> keys;
    std::vector<Tri> tris = readTriangles(mesh, request, keys);
    TangentReport report;
    if (tris.empty()) return report;
    weld(tris, keys);
    keys = {};
    linkNeighbours(tris);
    decideOrientations(tris);
    std::vector<Group> groups = formGroups(tris);

    // Each group's sum of its triangles' tangents, projected and weighted by angle.
    for (const Tri& tri : tris) {
        if (tri.degenerate || tri.tangent == Vec3(0)) continue;
        const Corners g(mesh, mesh.triangles[tri.index]);
        for (size_t k = 0; k < 3; ++k) {
            const Vec3 t = unitOrZero(project(tri.tangent, g.n[k]));
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
    for (const Tri& tri : tris) {
        if (tri.degenerate) continue;
        const Corners g(mesh, mesh.triangles[tri.index]);
        auto& corners = mesh.triangles[tri.index].corners;
        for (size_t k = 0; k < 3; ++k) corners[k].tangent = tangentOf(groups[tri.group[k]], g.n[k]);
        ++report.triangles;
    }
    // Corners of degenerate triangles: another group's tangent at the same vertex, else any.
    for (const Tri& tri : tris) {
        if (!tri.degenerate) continue;
        const Corners g(mesh, mesh.triangles[tri.index]);
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
