// The web build's stand-in for gltf_draco.cpp: Emscripten has no libdraco, so a Draco-compressed
// primitive is refused with a message (everything else in the file loads).

#include "glint/io/gltf/gltf_compression.h"

namespace glint::gltf {

void decodeDraco(const Context& ctx, Compression& c, size_t which) {
    DracoPrimitive& d = c.draco[which];
    d.decoded = true;
    ctx.fail(dracoLabel(ctx, d) +
             ": Draco-compressed meshes are not available in the web build of Glint (the "
             "command-line glint reads them; or save the file without compression)");
}

}  // namespace glint::gltf
