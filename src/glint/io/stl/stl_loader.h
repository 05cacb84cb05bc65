#pragma once
/// STL (stereolithography) meshes, binary and ASCII, read by Glint's own reader
/// (docs/scene-format.md, "PLY and STL files"). A file is binary when its size is exactly that
/// of the triangle count in its 84-byte header (84 + 50 bytes per triangle), ASCII when it starts
/// with `solid` and is text; a binary file whose header starts with "solid", as some exporters
/// write it, is still binary. Facet normals and binary attribute bytes are not read: a
/// triangle's front is the side its corners turn counter-clockwise on, as the format defines.
/// The result is a MeshData of separate triangles (three vertices each) in the file's units.

#include <string>
#include <string_view>
#include <vector>

#include "glint/core/error.h"
#include "glint/core/input_file.h"
#include "glint/scene/mesh.h"

namespace glint {

struct StlOptions {
    LoadLimits limits;
};

/// Parses the STL file `bytes`; `fileName` names it in diagnostics. Throws SceneError at the
/// first error (file:line:column in ASCII files; triangle and byte offset in binary ones), or if
/// the mesh would need more memory than `options.limits` allow; appends warnings.
MeshData parseStl(std::string_view bytes, const std::string& fileName,
                  std::vector<Diagnostic>& warnings, const StlOptions& options = {});

/// Reads (maps) and parses the STL file at `path`.
MeshData loadStl(const std::string& path, std::vector<Diagnostic>& warnings,
                 const StlOptions& options = {});

/// Bytes of a binary STL file of `triangles` triangles: 84 + 50 per triangle.
constexpr uint64_t binaryStlBytes(uint64_t triangles) { return 84 + 50 * triangles; }

}  // namespace glint
