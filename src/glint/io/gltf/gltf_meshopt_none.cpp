// The web build's stand-in for gltf_meshopt.cpp: Emscripten has no libmeshoptimizer, so a
// meshopt-compressed bufferView is refused with a message (everything else in the file loads).

#include "glint/io/gltf/gltf_compression.h"

namespace glint::gltf {

void decodeMeshoptData(const Context& ctx, const MeshoptView&, const std::string& label,
                       const unsigned char*, size_t, size_t, std::vector<unsigned char>&) {
    ctx.fail(label +
             ": meshopt-compressed meshes are not available in the web build of Glint (the "
             "command-line glint reads them; or save the file without compression)");
}

}  // namespace glint::gltf
