// Skinned meshes posed as glTF places them: each vertex by the weighted sum of its joints'
// matrices (the joint node's world transform times the skin's inverse bind matrix), in the
// pose the nodes' own transforms give (animations are not played). The node that places a
// skinned mesh does not move it: the glTF specification says to ignore its transform.

#include <cmath>
#include <map>
#include <optional>
#include <set>
#include <unordered_map>
#include <utility>
#include <vector>

#include "glint/io/gltf/gltf_internal.h"

namespace glint::gltf {
namespace {

constexpr uint32_t kNone = MeshData::kNone;

/// The world transforms of nodes, through their parents: joints may lie outside the scene
/// walked. Each is computed once.
class NodeWorlds {
  public:
    explicit NodeWorlds(const Context& ctx)
        : ctx_(ctx), parent_(ctx.model.nodes.size(), kRoot), world_(ctx.model.nodes.size()) {
        const auto& nodes = ctx.model.nodes;
        for (size_t i = 0; i < nodes.size(); ++i)
            for (int c : nodes[i].children) {
                if (c < 0 || static_cast<size_t>(c) >= nodes.size()) continue;  // walkNodes says
                int& p = parent_[static_cast<size_t>(c)];
                p = p == kRoot ? static_cast<int>(i) : kTwoParents;
            }
    }

    /// Node `node`'s world transform (`user` refers to it, for messages).
    const Mat4& operator()(size_t node, const std::string& user) {
        const auto& nodes = ctx_.model.nodes;
        std::vector<size_t> chain;  // node, its parent, ... up to a known one or a root
        for (size_t n = node; !world_[n];) {
            chain.push_back(n);
            if (chain.size() > nodes.size())
                ctx_.fail(describe("node", n, nodes[n].name) +
                          " is its own ancestor: glTF nodes form trees (" + user + ")");
            const int p = parent_[n];
            if (p == kTwoParents)
                ctx_.fail(describe("node", n, nodes[n].name) +
                          " has two parents: glTF nodes form trees (" + user + ")");
            if (p == kRoot) break;
            n = static_cast<size_t>(p);
        }
        for (auto it = chain.rbegin(); it != chain.rend(); ++it) {
            const int p = parent_[*it];
            const Mat4 local = localMatrix(ctx_, *it, describe("node", *it, nodes[*it].name));
            world_[*it] = p == kRoot ? local : *world_[static_cast<size_t>(p)] * local;
        }
        return *world_[node];
    }

  private:
    static constexpr int kRoot = -1, kTwoParents = -2;
    const Context& ctx_;
    std::vector<int> parent_;
    std::vector<std::optional<Mat4>> world_;
};

/// The linear part of an affine map, applied to vectors and normals.
struct Linear {
    Vec3 c[3];  ///< Columns.

    explicit Linear(const Mat4& m) {
        for (int j = 0; j < 3; ++j) c[j] = {m.m[0][j], m.m[1][j], m.m[2][j]};
    }
    Vec3 vector(const Vec3& v) const { return c[0] * v.x + c[1] * v.y + c[2] * v.z; }
    double determinant() const { return dot(c[0], cross(c[1], c[2])); }
    /// The normal by the inverse transpose, up to a positive factor: the cofactor matrix
    /// (det x the inverse transpose) with det's sign taken out. Defined for singular maps too.
    Vec3 normal(const Vec3& n) const {
        Vec3 v = cross(c[1], c[2]) * n.x + cross(c[2], c[0]) * n.y + cross(c[0], c[1]) * n.z;
        return determinant() < 0 ? -v : v;
    }
};

Vec3 applyPoint(const Mat4& m, const Vec3& p) {
    return {m.m[0][0] * p.x + m.m[0][1] * p.y + m.m[0][2] * p.z + m.m[0][3],
            m.m[1][0] * p.x + m.m[1][1] * p.y + m.m[1][2] * p.z + m.m[1][3],
            m.m[2][0] * p.x + m.m[2][1] * p.y + m.m[2][2] * p.z + m.m[2][3]};
}

/// A skin's joint matrices: world(joint) x inverse bind matrix (the identity without them).
std::vector<Mat4> jointMatrices(Context& ctx, NodeWorlds& worlds, int index) {
    const tinygltf::Skin& skin = ctx.model.skins[static_cast<size_t>(index)];
    const std::string label = describe("skin", static_cast<size_t>(index), skin.name);
    if (skin.joints.empty()) ctx.fail(label + " has no joints");
    std::vector<Mat4> inverseBind(skin.joints.size());
    if (skin.inverseBindMatrices != -1)
        inverseBind = readMatrices(ctx, skin.inverseBindMatrices, skin.joints.size(),
                                   "inverseBindMatrices of " + label);
    std::vector<Mat4> out(skin.joints.size());
    for (size_t j = 0; j < skin.joints.size(); ++j) {
        const int node = skin.joints[j];
        if (node < 0 || static_cast<size_t>(node) >= ctx.model.nodes.size())
            missing(ctx, "node", node, ctx.model.nodes.size(),
                    "joint " + std::to_string(j) + " of " + label);
        out[j] = worlds(static_cast<size_t>(node), "joint " + std::to_string(j) + " of " + label) *
                 inverseBind[j];
    }
    return out;
}

/// Poses `mesh` (read with `weights`) by a skin's `joints`; vertices without weights by
/// `fallback`.
void pose(Context& ctx, MeshData& mesh, VertexWeights& weights, const std::vector<Mat4>& joints,
          const Mat4& fallback, const std::string& skinLabel, const std::string& meshLabel) {
    weights.vertices.resize(mesh.positions.size());
    // Each vertex's matrix, blended from its joints' with its weights made to sum to 1.
    size_t unweighted = 0;
    std::vector<Mat4> matrices(mesh.positions.size());
    for (size_t i = 0; i < matrices.size(); ++i) {
        const VertexWeights::Vertex& v = weights.vertices[i];
        double sum = 0;
        for (size_t k = 0; k < VertexWeights::kInfluences; ++k) {
            if (v.joints[k] >= joints.size())
                ctx.fail(skinLabel + ": vertex " + std::to_string(i) + " of " + meshLabel +
                         " uses joint " + std::to_string(v.joints[k]) + ", but the skin has " +
                         std::to_string(joints.size()) +
                         (joints.size() == 1 ? " joint" : " joints"));
            sum += v.weights[k];
        }
        if (!(sum > 0)) {
            ++unweighted;
            matrices[i] = fallback;
            continue;
        }
        Mat4& m = matrices[i];
        m.m[0][0] = m.m[1][1] = m.m[2][2] = 0;
        for (size_t k = 0; k < VertexWeights::kInfluences; ++k) {
            if (v.weights[k] == 0) continue;
            const double w = v.weights[k] / sum;
            const Mat4& j = joints[v.joints[k]];
            for (int r = 0; r < 3; ++r)
                for (int c = 0; c < 4; ++c) m.m[r][c] += w * j.m[r][c];
        }
    }
    if (unweighted > 0)
        ctx.warn(meshLabel + ": " + std::to_string(unweighted) + " of its " +
                 std::to_string(matrices.size()) +
                 " vertices have no joint weights (no JOINTS_0 and WEIGHTS_0, or weights of 0): "
                 "they are placed by their node's transform");

    for (size_t i = 0; i < mesh.positions.size(); ++i) {
        const Vec3 p = applyPoint(matrices[i], Vec3(mesh.positions[i]));
        const Vec3f f(p);
        if (!std::isfinite(f.x) || !std::isfinite(f.y) || !std::isfinite(f.z))
            ctx.fail(skinLabel + ": vertex " + std::to_string(i) + " of " + meshLabel +
                     " is not finite once posed");
        mesh.positions[i] = f;
    }

    // Normals and tangents follow the vertex they belong to. One shared by vertices of other
    // weights (glTF allows primitives to share a NORMAL accessor, not their POSITION one) is
    // copied for each.
    auto follow = [&](uint32_t MeshData::Corner::*field, size_t count, auto copy) {
        std::vector<uint32_t> owner(count, kNone);
        std::unordered_map<uint64_t, uint32_t> copies;
        for (MeshData::Triangle& t : mesh.triangles)
            for (MeshData::Corner& c : t.corners) {
                uint32_t& a = c.*field;
                if (a == kNone) continue;
                if (owner[a] == kNone) owner[a] = c.position;
                if (owner[a] == c.position ||
                    weights.vertices[owner[a]] == weights.vertices[c.position])
                    continue;
                const uint64_t key = uint64_t(a) << 32 | c.position;
                auto [it, added] = copies.emplace(key, static_cast<uint32_t>(owner.size()));
                if (added) {
                    copy(a);
                    owner.push_back(c.position);
                }
                a = it->second;
            }
        return owner;
    };
    const std::vector<uint32_t> normalOwner =
        follow(&MeshData::Corner::normal, mesh.normals.size(),
               [&](uint32_t a) { mesh.normals.push_back(mesh.normals[a]); });
    for (size_t i = 0; i < mesh.normals.size(); ++i) {
        if (normalOwner[i] == kNone) continue;
        const Vec3 n = Linear(matrices[normalOwner[i]]).normal(Vec3(mesh.normals[i]));
        const double len = length(n);
        mesh.normals[i] = Vec3f(len > 0 && std::isfinite(len) ? n / len : Vec3(0));
    }
    const std::vector<uint32_t> tangentOwner =
        follow(&MeshData::Corner::tangent, mesh.tangents.size(),
               [&](uint32_t a) { mesh.tangents.push_back(mesh.tangents[a]); });
    for (size_t i = 0; i < mesh.tangents.size(); ++i) {
        if (tangentOwner[i] == kNone) continue;
        const Linear m(matrices[tangentOwner[i]]);
        auto& t = mesh.tangents[i];
        const Vec3 v = m.vector(Vec3(t[0], t[1], t[2]));
        const double len = length(v);
        const Vec3 unit = len > 0 && std::isfinite(len) ? v / len : Vec3(0);
        // A mirroring matrix turns the frame's handedness.
        const float sign = m.determinant() < 0 ? -t[3] : t[3];
        t = {float(unit.x), float(unit.y), float(unit.z), sign};
    }
}

}  // namespace

void poseSkins(Context& ctx, Model& out, const std::vector<SkinnedPlacement>& skinned,
               std::vector<VertexWeights>& weights) {
    NodeWorlds worlds(ctx);
    // Whether each mesh is used otherwise than by one skin: then each skin poses a copy.
    const size_t meshes = out.meshes.size();
    std::vector<int> skinOf(out.placements.size(), -1);
    for (const SkinnedPlacement& s : skinned) skinOf[s.placement] = s.skin;
    std::vector<std::set<int>> usedBy(meshes);  // skins, and -1 for no skin
    for (size_t i = 0; i < out.placements.size(); ++i)
        usedBy[out.placements[i].mesh].insert(skinOf[i]);

    std::map<int, std::vector<Mat4>> joints;             // by skin
    std::map<std::pair<uint32_t, int>, uint32_t> posed;  // (mesh, skin) -> posed mesh
    for (const SkinnedPlacement& s : skinned) {
        ModelPlacement& placement = out.placements[s.placement];
        const uint32_t mesh = placement.mesh;
        auto [it, added] = posed.emplace(std::pair(mesh, s.skin), mesh);
        if (added) {
            auto j = joints.find(s.skin);
            if (j == joints.end())
                j = joints.emplace(s.skin, jointMatrices(ctx, worlds, s.skin)).first;
            if (usedBy[mesh].size() > 1) {
                it->second = static_cast<uint32_t>(out.meshes.size());
                MeshData copy = out.meshes[mesh];
                out.meshes.push_back(std::move(copy));
            }
            const tinygltf::Skin& skin = ctx.model.skins[static_cast<size_t>(s.skin)];
            pose(ctx, out.meshes[it->second], weights[mesh], j->second, s.nodeWorld,
                 describe("skin", static_cast<size_t>(s.skin), skin.name),
                 describe("mesh", mesh, ctx.model.meshes[mesh].name));
        }
        placement.mesh = it->second;
    }
    // Meshes only skins use were copied for each: the unposed one is not placed.
    for (size_t m = 0; m < meshes; ++m)
        if (usedBy[m].size() > 1 && !usedBy[m].contains(-1)) out.meshes[m] = MeshData();
}

}  // namespace glint::gltf
