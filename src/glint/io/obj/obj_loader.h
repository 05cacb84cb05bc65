#pragma once
/// Wavefront OBJ meshes with their MTL materials and diffuse textures. tinyobjloader reads the
/// statements; Glint checks every index and number, triangulates polygons and maps the MTL
/// materials to its own (docs/scene-format.md, "Meshes"). The result is a MeshData in the
/// mesh's own space; scene/mesh.h places it in a scene.

#include <string>
#include <string_view>
#include <vector>

#include "glint/core/error.h"
#include "glint/core/input_file.h"
#include "glint/scene/mesh.h"

namespace glint {

struct ObjOptions {
    LoadLimits limits;
    /// MTL text used for every `mtllib` instead of the files it names (tests, the fuzzer). With
    /// it, or when limits.readFiles is false, no texture image is read either.
    const std::string* mtlText = nullptr;
};

/// Parses the OBJ text `text`; `fileName` names it in diagnostics, and its directory is where
/// `mtllib` files are found. Throws SceneError (file:line:col where known) at the first error,
/// or if the mesh would need more memory than `options.limits` allow; appends warnings.
MeshData parseObj(std::string_view text, const std::string& fileName,
                  std::vector<Diagnostic>& warnings, const ObjOptions& options = {});

/// Reads and parses the OBJ file at `path`.
MeshData loadObj(const std::string& path, std::vector<Diagnostic>& warnings,
                 const ObjOptions& options = {});

/// Bytes a mesh file of this many statements needs once loaded and placed in a scene: the
/// MeshData, the scene's primitives and BVH, and placing's temporaries (upper bounds).
size_t objBytes(size_t positions, size_t normals, size_t uvs, size_t triangles);

}  // namespace glint
