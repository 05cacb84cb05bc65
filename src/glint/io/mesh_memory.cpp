#include "glint/io/mesh_memory.h"

#include <cstdio>

#include "glint/core/error.h"
#include "glint/core/system.h"
#include "glint/scene/mesh.h"

namespace glint {

double meshBytes(const MeshCounts& c) {
    double mesh = c.positions * sizeof(Vec3f) + c.normals * sizeof(Vec3f) +
                  c.uvs * sizeof(TexCoord) + c.colors * sizeof(std::array<float, 4>) +
                  c.triangles * sizeof(MeshData::Triangle);
    // The scene's estimate per triangle, scaled: the counts may exceed size_t's range.
    const double perTriangle = double(Scene::estimateBytes(1000, 0, 0, 0, 0)) / 1000;
    const double perNormal = double(Scene::estimateBytes(1000, 0, 0, 1000, 0)) / 1000 - perTriangle;
    const double perUv = double(Scene::estimateBytes(1000, 0, 0, 0, 1000)) / 1000 - perTriangle;
    double scene =
        c.triangles * (perTriangle + (c.withNormals ? perNormal : 0) + (c.withUvs ? perUv : 0) +
                       (c.withColors ? double(sizeof(TriangleExtras)) : 0));
    double placing = c.positions * (sizeof(Vec3) + sizeof(bool)) + c.normals * sizeof(Vec3);
    return mesh + scene + placing;
}

void checkMeshMemory(const MeshCounts& counts, const std::string& file, const LoadLimits& limits) {
    double needed = meshBytes(counts);
    size_t available = memoryAvailable(limits);
    if (available > 0 && needed > double(available)) {
        char triangles[64];
        std::snprintf(triangles, sizeof triangles, "%.0f", counts.triangles);
        throw SceneError({file, 0, 0}, "the mesh needs about " + formatBytes(needed) +
                                           " of memory (" + triangles +
                                           " triangles), more than the " +
                                           formatBytes(double(available)) + " available");
    }
}

}  // namespace glint
