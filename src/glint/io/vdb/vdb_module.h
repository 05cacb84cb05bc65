#pragma once
/// The OpenVDB module (libglint_vdb.so): what it exports, and the reader inside it. OpenVDB links
/// TBB, Boost.Iostreams, blosc, log4cplus and their codecs, whose loading and static
/// constructors cost every run of a program linking them 0.05 s and 28 MB (docs/performance.md,
/// "Start-up"); so the glint program and the Python module link none of them, and
/// loadVdbDensity (vdb_reader.h) loads this module the first time a .vdb file is read.
///
/// Built as its own CMake target, glint_vdb (src/CMakeLists.txt), beside the glint program; the
/// fuzzer links the reader directly.

#include <memory>
#include <string>

#include "glint/core/input_file.h"
#include "glint/scene/medium.h"

namespace glint {

/// The module's file name, and the symbol it exports: a VdbReadFunction.
inline constexpr const char* kVdbModuleFile = "libglint_vdb.so";
inline constexpr const char* kVdbModuleEntry = "glint_vdb_read";

/// Reads a grid as loadVdbDensity promises into `grid`; on failure leaves it null and puts the
/// message (as loadVdbDensity would throw it) in `error`. Nothing is thrown across the module's
/// boundary.
using VdbReadFunction = void (*)(const std::string& path, const std::string& gridName,
                                 const LoadLimits& limits, std::shared_ptr<const DensityGrid>* grid,
                                 std::string* error);

/// The reader itself (vdb_reader.cpp, in the module): loadVdbDensity's contract, throwing
/// RenderError.
std::shared_ptr<const DensityGrid> readVdbDensity(const std::string& path,
                                                  const std::string& gridName,
                                                  const LoadLimits& limits);

}  // namespace glint
