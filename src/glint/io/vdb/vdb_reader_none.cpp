// The stand-in for vdb_reader.cpp in builds without OpenVDB (the web build, where Emscripten has
// no OpenVDB; native builds configured with GLINT_OPENVDB=OFF): every .vdb file is refused.

#include "glint/core/error.h"
#include "glint/io/vdb/vdb_reader.h"

namespace glint {

std::shared_ptr<const DensityGrid> loadVdbDensity(const std::string& path, const std::string&,
                                                  const LoadLimits&) {
    throw RenderError("cannot read density grid '" + path +
                      "': this build of Glint reads no OpenVDB files (the command-line glint "
                      "built with libopenvdb-dev does)");
}

}  // namespace glint
