// The OpenVDB module's one export (vdb_module.h): readVdbDensity behind a function that throws
// nothing across the module's boundary.

#include <exception>
#include <type_traits>

#include "glint/io/vdb/vdb_module.h"

extern "C" __attribute__((visibility("default"))) void glint_vdb_read(
    const std::string& path, const std::string& gridName, const glint::LoadLimits& limits,
    std::shared_ptr<const glint::DensityGrid>* grid, std::string* error) {
    try {
        *grid = glint::readVdbDensity(path, gridName, limits);
    } catch (const std::exception& e) {
        *error = e.what();
    } catch (...) {
        *error = "cannot read density grid '" + path + "': an unknown error";
    }
}

// The type the loader calls it as.
static_assert(std::is_same_v<decltype(&glint_vdb_read), glint::VdbReadFunction>);
