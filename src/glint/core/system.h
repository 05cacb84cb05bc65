#pragma once
/// What the machine offers: memory (threads: core/parallel.h).

#include <cstddef>
#include <string>

namespace glint {

/// Memory the system could give this process now without swapping, in bytes (MemAvailable
/// from /proc/meminfo; the physical memory if that cannot be read).
size_t availableMemoryBytes();

/// "1.5 GiB", "300 MiB".
std::string formatBytes(double bytes);

}  // namespace glint
