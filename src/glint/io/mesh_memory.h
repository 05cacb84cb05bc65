#pragma once
/// The memory a mesh read from a file will take, checked before the file's arrays are allocated
/// (PLY, STL): a file may claim any number of vertices and faces, and a loader allocates only
/// after its header's counts are known to fit both the file's bytes and the memory available.

#include <string>

#include "glint/core/input_file.h"

namespace glint {

/// How much a mesh file holds (counts as numbers: a header may claim more than size_t holds).
struct MeshCounts {
    double positions = 0, normals = 0, uvs = 0, colors = 0;
    double triangles = 0;
    bool withNormals = false, withUvs = false, withColors = false;  ///< Per triangle.
};

/// Bytes the mesh needs once read and placed in a scene: its MeshData, the scene's triangles,
/// their attributes and BVH, and placing's temporaries (upper bounds, as objBytes).
double meshBytes(const MeshCounts& counts);

/// Throws SceneError at `file` ("the mesh needs about 3.1 GiB of memory (... triangles), more
/// than the 1.2 GiB available") if `counts` need more than `limits` allow.
void checkMeshMemory(const MeshCounts& counts, const std::string& file, const LoadLimits& limits);

}  // namespace glint
