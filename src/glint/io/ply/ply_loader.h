#pragma once
/// PLY (Stanford polygon file) meshes, ASCII and binary of either byte order, read by Glint's own
/// reader: vertex positions, normals, colours and texture coordinates, faces of any number of
/// vertices (split as fans) and the triangle strips of the Stanford tools (docs/scene-format.md,
/// "PLY and STL files"). Every count in the header is checked against the bytes the file has
/// and the memory available before anything is allocated. The result is a MeshData in the
/// mesh's own space; scene/mesh.h places it in a scene.

#include <string>
#include <string_view>
#include <vector>

#include "glint/core/error.h"
#include "glint/core/input_file.h"
#include "glint/scene/mesh.h"

namespace glint {

struct PlyOptions {
    LoadLimits limits;
};

/// Parses the PLY file `bytes`; `fileName` names it in diagnostics. Throws SceneError at the
/// first error (file:line:column in the header and in ASCII data; file, element, record and
/// byte offset in binary data), or if the mesh would need more memory than `options.limits`
/// allow; appends warnings (faces of fewer than 3 vertices, zero normals, data after the last
/// element).
MeshData parsePly(std::string_view bytes, const std::string& fileName,
                  std::vector<Diagnostic>& warnings, const PlyOptions& options = {});

/// Reads (maps) and parses the PLY file at `path`.
MeshData loadPly(const std::string& path, std::vector<Diagnostic>& warnings,
                 const PlyOptions& options = {});

}  // namespace glint
