#pragma once
/// What every loader checks before it reads a file (scenes, meshes, material libraries,
/// textures), and the limits they share.

#include <cstddef>
#include <memory>
#include <string>

#include "glint/core/mapped_file.h"

namespace glint {

/// Largest input file Glint reads (bytes); bigger files are refused before reading.
constexpr long long kMaxSceneFileBytes = 1LL << 30;

/// Resources a scene may take, checked before anything is allocated.
struct LoadLimits {
    size_t memoryBytes = 0;  ///< 0: the memory the machine has available now.
    /// Whether loading may read the other files a scene names (`mesh`, `texture`, an OBJ's
    /// `mtllib` and `map_Kd`). The fuzzers turn it off: their input must not reach the disk.
    bool readFiles = true;
};

/// Why `path` cannot be read as an input file (it is missing, a directory, not a regular file,
/// or larger than `maxBytes`), or an empty string if it can.
std::string inputFileProblem(const std::string& path, long long maxBytes = kMaxSceneFileBytes);

/// `path` checked by inputFileProblem() and mapped into memory; null, with `problem` saying
/// why, if it cannot be read.
std::unique_ptr<MappedFile> mapInputFile(const std::string& path, std::string& problem);

/// `limits.memoryBytes`, or the memory available now when that is 0.
size_t memoryAvailable(const LoadLimits& limits);

}  // namespace glint
