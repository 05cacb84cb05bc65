#include "glint/scene/mesh.h"

#include <cmath>
#include <map>
#include <memory>
#include <utility>

#include "glint/core/error.h"

namespace glint {

size_t meshPlacementBytes(size_t positions, size_t normals) {
    return positions * (sizeof(Vec3) + sizeof(bool)) + normals * sizeof(Vec3);
}

namespace {

[[noreturn]] void beyondRange(const MeshData& mesh, uint32_t vertex) {
    throw SceneError({mesh.name, 0, 0},
                     "vertex " + std::to_string(vertex + 1) +
                         " lies beyond the supported coordinate range (1e18) once placed by "
                         "the transform");
}

/// Whether `t` mirrors space (its linear part has a negative determinant).
bool mirrors(const Transform& t) {
    Vec3 x = t.vector({1, 0, 0}), y = t.vector({0, 1, 0}), z = t.vector({0, 0, 1});
    return dot(cross(x, y), z) < 0;
}

/// Adds `mesh`'s triangles to `target` placed by `worldFromObject`, with its materials and
/// textures added to `scene` (addMesh, and the shared meshes of MeshPlacer).
MeshPlacement addTriangles(Scene& scene, Primitives& target, const MeshData& mesh,
                           const Transform& worldFromObject, uint32_t defaultMaterial,
                           std::vector<uint32_t>* kept = nullptr) {
    // Each vertex and normal is placed once, however many triangles share it.
    LargeVector<Vec3> world(mesh.positions.size());
    std::vector<bool> placedInRange(mesh.positions.size());
    for (size_t i = 0; i < world.size(); ++i) {
        world[i] = worldFromObject.point(Vec3(mesh.positions[i]));
        placedInRange[i] = withinCoordinateRange(world[i]);
    }
    // Normals are mapped by the inverse transpose and not renormalised: interpolating them
    // (and normalising the result) then gives exactly the mapped interpolated normal, which
    // is what an instance of the mesh shades with.
    LargeVector<Vec3> normals(mesh.normals.size());
    for (size_t i = 0; i < normals.size(); ++i) {
        Vec3 n = worldFromObject.normal(Vec3(mesh.normals[i]));
        normals[i] = std::isfinite(length(n)) ? n : Vec3(0);
    }

    std::vector<uint32_t> materialIds(mesh.materials.size());
    for (size_t i = 0; i < mesh.materials.size(); ++i) {
        Material m = mesh.materials[i].material;
        if (mesh.materials[i].texture) m.texture = scene.addTexture(*mesh.materials[i].texture);
        if (mesh.materials[i].pbr) m.pbr = scene.addPbrMaterial(*mesh.materials[i].pbr);
        if (mesh.materials[i].interior) m.interior = scene.addMedium(*mesh.materials[i].interior);
        materialIds[i] = scene.addMaterial(m);
    }

    // A mirroring transform would turn the winding, and with it the face normal, inside out:
    // corners are taken in the other order then, so the front stays the front (as the mapped
    // face normal of an instance does).
    const bool mirrored = mirrors(worldFromObject);
    const int second = mirrored ? 2 : 1;
    const bool anyExtras = !mesh.uv1s.empty() || !mesh.colors.empty() || !mesh.tangents.empty();
    target.reserve(mesh.triangles.size(), 0);
    target.reserveAttributes(mesh.normalTriangles, mesh.uvTriangles);
    MeshPlacement placed;
    for (const MeshData::Triangle& t : mesh.triangles) {
        Vec3 p[3], n[3];
        TexCoord uv[3];
        TriangleExtras extras;
        for (int k = 0; k < 3; ++k) {
            const MeshData::Corner& c = t.corners[k == 0 ? 0 : k == 1 ? second : 3 - second];
            if (!placedInRange[c.position]) beyondRange(mesh, c.position);
            p[k] = world[c.position];
            if (c.normal != MeshData::kNone) n[k] = normals[c.normal];
            if (c.uv != MeshData::kNone) uv[k] = mesh.uvs[c.uv];
            if (!anyExtras) continue;
            const auto kk = static_cast<size_t>(k);
            if (c.uv1 != MeshData::kNone) {
                extras.uv1[kk] = mesh.uv1s[c.uv1];
                extras.present |= TriangleExtras::kUv1;
            }
            if (c.color != MeshData::kNone) {
                extras.color[kk] = mesh.colors[c.color];
                extras.present |= TriangleExtras::kColor;
            }
            if (c.tangent != MeshData::kNone) {
                const auto& tg = mesh.tangents[c.tangent];
                Vec3 wt = worldFromObject.vector(Vec3(tg[0], tg[1], tg[2]));
                const float sign = (tg[3] < 0) != mirrored ? -1.0f : 1.0f;
                extras.tangent[kk] = {static_cast<float>(wt.x), static_cast<float>(wt.y),
                                      static_cast<float>(wt.z), sign};
                extras.present |= TriangleExtras::kTangent;
            }
        }
        const MeshData::Corner& c0 = t.corners[0];
        uint32_t material =
            t.material == MeshData::kNone ? defaultMaterial : materialIds[t.material];
        bool ok = target.addTriangle(p[0], p[1], p[2], c0.normal != MeshData::kNone ? n : nullptr,
                                     c0.uv != MeshData::kNone ? uv : nullptr,
                                     anyExtras ? &extras : nullptr, material);
        ++(ok ? placed.added : placed.degenerate);
        if (ok && kept) kept->push_back(static_cast<uint32_t>(&t - mesh.triangles.data()));
    }
    return placed;
}

/// The deformation of the triangles `kept` of `mesh` (placed as they are, in mesh space).
std::shared_ptr<const DeformingMesh> deformation(const MeshData& mesh,
                                                 const std::vector<uint32_t>& kept) {
    using Corners = DeformingMesh::Corners;
    const size_t keys = mesh.positionKeys.size();
    const bool normals = mesh.normalKeys.size() == keys;
    std::vector<std::vector<Corners>> vertices(keys), cornerNormals(normals ? keys : 0);
    for (size_t k = 0; k < keys; ++k) {
        const LargeVector<Vec3f>& p = mesh.positionKeys[k];
        if (p.size() != mesh.positions.size())
            throw SceneError({mesh.name, 0, 0}, "a deforming mesh's keys differ in size");
        vertices[k].reserve(kept.size());
        for (uint32_t i : kept) {
            const auto& c = mesh.triangles[i].corners;
            vertices[k].push_back({p[c[0].position], p[c[1].position], p[c[2].position]});
        }
        if (!normals) continue;
        const LargeVector<Vec3f>& n = mesh.normalKeys[k];
        if (n.size() != mesh.normals.size())
            throw SceneError({mesh.name, 0, 0}, "a deforming mesh's normal keys differ in size");
        for (uint32_t i : kept) {
            const auto& c = mesh.triangles[i].corners;
            cornerNormals[k].push_back(
                c[0].normal == MeshData::kNone
                    ? Corners{}
                    : Corners{n[c[0].normal], n[c[1].normal], n[c[2].normal]});
        }
    }
    return std::make_shared<const DeformingMesh>(std::move(vertices), std::move(cornerNormals));
}

/// Whether some triangle of `mesh` takes the placing default material.
bool usesDefaultMaterial(const MeshData& mesh) {
    for (const MeshData::Triangle& t : mesh.triangles)
        if (t.material == MeshData::kNone) return true;
    return false;
}

}  // namespace

MeshPlacement addMesh(Scene& scene, const MeshData& mesh, const Transform& worldFromObject,
                      uint32_t defaultMaterial) {
    return addTriangles(scene, scene.primitives, mesh, worldFromObject, defaultMaterial);
}

void MeshPlacer::add(const MeshData& mesh, const Transform& worldFromObject,
                     uint32_t defaultMaterial, FileLoc where, std::string what,
                     std::shared_ptr<const MotionPath> motion) {
    placements_.push_back({&mesh, worldFromObject, defaultMaterial, std::move(where),
                           std::move(what), std::move(motion)});
}

std::vector<MeshPlacement> MeshPlacer::place(Scene& scene, std::vector<Diagnostic>* warnings) {
    // Placements that can share: the same mesh, and the same default material where the mesh
    // uses it.
    using Key = std::pair<const MeshData*, uint32_t>;
    std::map<const MeshData*, bool> usesDefault;
    std::map<Key, size_t> uses;
    std::vector<Key> keys;
    for (const Placement& p : placements_) {
        auto [it, added] = usesDefault.try_emplace(p.mesh, false);
        if (added) it->second = usesDefaultMaterial(*p.mesh);
        keys.push_back({p.mesh, it->second ? p.defaultMaterial : MeshData::kNone});
        ++uses[keys.back()];
    }

    struct Shared {
        uint32_t index;
        MeshPlacement stored;
    };
    std::map<Key, Shared> shared;
    std::vector<MeshPlacement> results;
    for (size_t i = 0; i < placements_.size(); ++i) {
        const Placement& p = placements_[i];
        try {
            const bool deforms = p.mesh->positionKeys.size() >= 2;
            if (uses[keys[i]] == 1 && !p.motion && !deforms) {
                results.push_back(addMesh(scene, *p.mesh, p.worldFromObject, p.defaultMaterial));
                continue;
            }
            auto it = shared.find(keys[i]);
            if (it == shared.end()) {
                Primitives prims;
                std::vector<uint32_t> kept;
                MeshPlacement stored = addTriangles(scene, prims, *p.mesh, Transform(),
                                                    p.defaultMaterial, deforms ? &kept : nullptr);
                if (deforms) prims.setDeformation(deformation(*p.mesh, kept));
                // A mesh whose every triangle is degenerate has nothing to place.
                uint32_t index = prims.triangleCount() == 0 ? MeshData::kNone
                                                            : scene.addSharedMesh(std::move(prims));
                it = shared.emplace(keys[i], Shared{index, stored}).first;
            }
            results.push_back(it->second.stored);
            if (it->second.index == MeshData::kNone) continue;
            // The placed mesh must lie in range, as placed vertices must.
            const Bounds3f& b = scene.primitives.addInstance(it->second.index, p.worldFromObject);
            if (p.motion)
                scene.primitives.setMotion(scene.primitives.boundedCount() - 1, *p.motion);
            if (!withinCoordinateRange(Vec3(b.lo)) || !withinCoordinateRange(Vec3(b.hi)))
                throw SceneError({p.mesh->name, 0, 0},
                                 "the mesh lies beyond the supported coordinate range (1e18) "
                                 "once placed by the transform");
        } catch (const SceneError& e) {
            if (p.where.file.empty()) throw;
            throw SceneError(p.where, p.what + ": " + e.diagnostic().message);
        }
    }
    // Degenerate triangles: one warning, at the first placement that had some.
    for (size_t i = 0; warnings && i < results.size(); ++i) {
        if (results[i].degenerate == 0) continue;
        const Placement& p = placements_[i];
        Diagnostic d;
        d.message = std::to_string(results[i].degenerate) +
                    " triangles have zero area once placed and are skipped";
        if (p.where.file.empty()) {
            d.loc.file = p.mesh->name;
        } else {
            d.loc = p.where;
            d.message = p.what + ": " + d.message + " (reported once)";
        }
        warnings->push_back(std::move(d));
        break;
    }
    placements_.clear();
    return results;
}

}  // namespace glint
