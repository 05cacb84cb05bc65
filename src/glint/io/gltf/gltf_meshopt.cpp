// The meshopt codec's part of compressed glTF (gltf_compression.cpp checks the extension's
// rules first): libmeshoptimizer 0.18, Debian 12's. The web build, which has no
// libmeshoptimizer, links gltf_meshopt_none.cpp instead.

#include <meshoptimizer.h>

#include "glint/io/gltf/gltf_compression.h"

namespace glint::gltf {

void decodeMeshoptData(const Context& ctx, const MeshoptView& m, const std::string& label,
                       const unsigned char* source, size_t count, size_t stride,
                       std::vector<unsigned char>& out) {
    int status = 0;
    const char* what = "ATTRIBUTES";
    switch (m.mode) {
        case MeshoptMode::Attributes:
            if (m.byteLength > 0 && (source[0] & 0xF0) == 0xA0 && (source[0] & 0x0F) > 0)
                ctx.fail(label + ": its data is in version " + std::to_string(source[0] & 0x0F) +
                         " of the attribute codec, which Debian 12's libmeshoptimizer 0.18 " +
                         "does not decode (it decodes version 0)");
            status = meshopt_decodeVertexBuffer(out.data(), count, stride, source, m.byteLength);
            break;
        case MeshoptMode::Triangles:
            what = "TRIANGLES";
            status = meshopt_decodeIndexBuffer(out.data(), count, stride, source, m.byteLength);
            break;
        case MeshoptMode::Indices:
            what = "INDICES";
            status = meshopt_decodeIndexSequence(out.data(), count, stride, source, m.byteLength);
            break;
    }
    if (status != 0)
        ctx.fail(label + ": its " + what + " data (" + std::to_string(m.byteLength) +
                 " bytes in buffer " + std::to_string(m.buffer) +
                 ") is corrupt or not what count and byteStride say (libmeshoptimizer error " +
                 std::to_string(status) + ")");
    switch (m.filter) {
        case MeshoptFilter::Octahedral:
            meshopt_decodeFilterOct(out.data(), count, stride);
            break;
        case MeshoptFilter::Quaternion:
            meshopt_decodeFilterQuat(out.data(), count, stride);
            break;
        case MeshoptFilter::Exponential:
            meshopt_decodeFilterExp(out.data(), count, stride);
            break;
        default:
            break;
    }
}

}  // namespace glint::gltf
