#include "glint/scene/mesh.h"

#include <cmath>

#include "glint/core/error.h"

namespace glint {

size_t meshPlacementBytes(size_t positions, size_t normals) {
    return positions * (sizeof(Vec3) + sizeof(bool)) + normals * sizeof(Vec3);
}

MeshPlacement addMesh(Scene& scene, const MeshData& mesh, const Transform& worldFromObject,
                      uint32_t defaultMaterial) {
    // Each vertex and normal is placed once, however many triangles share it.
    LargeVector<Vec3> world(mesh.positions.size());
    std::vector<bool> inRange(mesh.positions.size());
    for (size_t i = 0; i < world.size(); ++i) {
        world[i] = worldFromObject.point(Vec3(mesh.positions[i]));
        const Vec3& p = world[i];
        inRange[i] = std::abs(p.x) <= kMaxCoordinate && std::abs(p.y) <= kMaxCoordinate &&
                     std::abs(p.z) <= kMaxCoordinate;
    }
    LargeVector<Vec3> normals(mesh.normals.size());
    for (size_t i = 0; i < normals.size(); ++i) {
        Vec3 n = worldFromObject.normal(Vec3(mesh.normals[i]));
        double len = length(n);
        normals[i] = len > 0 && std::isfinite(len) ? n / len : Vec3(0);
    }

    std::vector<uint32_t> materialIds(mesh.materials.size());
    for (size_t i = 0; i < mesh.materials.size(); ++i) {
        Material m = mesh.materials[i].material;
        if (mesh.materials[i].texture) m.texture = scene.addTexture(*mesh.materials[i].texture);
        materialIds[i] = scene.addMaterial(m);
    }

    scene.primitives.reserve(mesh.triangles.size(), 0);
    scene.primitives.reserveAttributes(mesh.normalTriangles, mesh.uvTriangles);
    MeshPlacement placed;
    for (const MeshData::Triangle& t : mesh.triangles) {
        Vec3 p[3], n[3];
        TexCoord uv[3];
        for (int k = 0; k < 3; ++k) {
            const MeshData::Corner& c = t.corners[k];
            if (!inRange[c.position])
                throw SceneError({mesh.name, 0, 0},
                                 "vertex " + std::to_string(c.position + 1) +
                                     " lies beyond the supported coordinate range (1e18) once "
                                     "placed by the transform");
            p[k] = world[c.position];
            if (c.normal != MeshData::kNone) n[k] = normals[c.normal];
            if (c.uv != MeshData::kNone) uv[k] = mesh.uvs[c.uv];
        }
        const MeshData::Corner& c0 = t.corners[0];
        uint32_t material =
            t.material == MeshData::kNone ? defaultMaterial : materialIds[t.material];
        bool ok = scene.primitives.addTriangle(p[0], p[1], p[2],
                                               c0.normal != MeshData::kNone ? n : nullptr,
                                               c0.uv != MeshData::kNone ? uv : nullptr, material);
        ++(ok ? placed.added : placed.degenerate);
    }
    return placed;
}

}  // namespace glint
