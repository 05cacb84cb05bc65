// loadVdbDensity (vdb_reader.h) in builds with OpenVDB: through the OpenVDB module
// (vdb_module.h), loaded the first time a file is read.

#include <mutex>

#include "glint/core/error.h"
#include "glint/core/module.h"
#include "glint/io/vdb/vdb_module.h"
#include "glint/io/vdb/vdb_reader.h"

#ifndef GLINT_BUILD_MODULE_DIR
#define GLINT_BUILD_MODULE_DIR ""
#endif

namespace glint {

std::shared_ptr<const DensityGrid> loadVdbDensity(const std::string& path,
                                                  const std::string& gridName,
                                                  const LoadLimits& limits) {
    static std::once_flag once;
    static VdbReadFunction read = nullptr;
    static std::string why;
    std::call_once(once, [] {
        const LoadedModule module = loadModule(kVdbModuleFile, GLINT_BUILD_MODULE_DIR, &why);
        if (!module.handle) return;
        read = reinterpret_cast<VdbReadFunction>(moduleSymbol(module, kVdbModuleEntry));
        if (!read) why = std::string(kVdbModuleFile) + " exports no " + kVdbModuleEntry;
    });
    if (!read)
        throw RenderError("cannot read density grid '" + path + "': Glint's OpenVDB module (" +
                          kVdbModuleFile +
                          ", built beside the glint program) could not be loaded: " + why);
    std::shared_ptr<const DensityGrid> grid;
    std::string error;
    read(path, gridName, limits, &grid, &error);
    if (!grid) throw RenderError(error);
    return grid;
}

}  // namespace glint
