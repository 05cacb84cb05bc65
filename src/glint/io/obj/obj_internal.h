#pragma once
// Shared by obj_loader.cpp (the OBJ statements) and obj_materials.cpp (MTL libraries and their
// textures). Internal to glint/io: use obj_loader.h.

#include <tiny_obj_loader.h>

#include <map>
#include <memory>
#include <streambuf>
#include <string>
#include <string_view>
#include <vector>

#include "glint/core/error.h"
#include "glint/core/input_file.h"
#include "glint/scene/mesh.h"

namespace glint::obj {

/// A read-only stream buffer over text in memory, for tinyobjloader's std::istream interface
/// without a copy. Its read position tells which line the library has just read.
class TextBuf : public std::streambuf {
  public:
    explicit TextBuf(std::string_view text) {
        char* p = const_cast<char*>(text.data());  // never written: only the get area is used
        setg(p, p, p + text.size());
    }
    size_t offset() const { return static_cast<size_t>(gptr() - eback()); }
};

/// tinyobjloader's warnings `text` (one per line) about `file`, as Glint's: at the line a
/// warning names ("(line 5.)", "(line 5 in .mtl.)"), else at the file, in Glint's words where
/// Glint knows the warning.
std::vector<Diagnostic> libraryWarnings(std::string_view text, const std::string& file);

/// Line and column (1-based) in `text` of the statement tinyobjloader has just read, given the
/// read position `offset` just past it. Lines end at LF, CR or CR LF, as the library counts them.
/// `token` > 0 gives the column of the line's token of that number (0: the first one).
FileLoc statementAt(std::string_view text, size_t offset, const std::string& file, int token = 0);

/// The texture images a mesh has read, by path (and encoding): each is read once.
using TextureCache = std::map<std::string, std::shared_ptr<const TextureImage>>;

/// What Glint needs to know of an MTL material beyond what tinyobjloader keeps.
struct MtlEntry {
    int line = 0;  ///< Of its `newmtl`.
    bool hasKa = false, hasKd = false, hasIllum = false;
    /// Whether it uses the PBR extensions (Pr, Pm, Ps, map_Pr, map_Pm, norm, ...): then it
    /// becomes a physically based material (MeshMaterial::pbr).
    bool pbr = false;
};

/// The materials of an MTL text in the order tinyobjloader's LoadMtl adds them.
std::vector<MtlEntry> scanMtl(std::string_view text);

/// Where an MTL library came from, for messages and for its texture files.
struct MtlSource {
    std::string file;        ///< As named in messages.
    std::string textureDir;  ///< Directory texture names are relative to ("" when none).
    bool readTextures = true;
};

/// Glint's material for MTL material `m` (docs/scene-format.md, "MTL materials"), reading its
/// diffuse texture through `cache`. Throws SceneError at the `newmtl` line for values that
/// are not finite; a texture that cannot be read is a warning (the material keeps its Kd).
MeshMaterial mapMtlMaterial(const tinyobj::material_t& m, const MtlEntry& entry,
                            const MtlSource& source, TextureCache& cache,
                            std::vector<Diagnostic>& warnings, const LoadLimits& limits);

}  // namespace glint::obj
