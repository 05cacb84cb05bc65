#pragma once
/// What the machine offers: threads and memory.

#include <cstddef>
#include <string>
#include <thread>

namespace glint {

/// The number of threads the machine runs at once (at least 1): what "all threads" means.
inline int hardwareThreads() {
    unsigned n = std::thread::hardware_concurrency();
    return n ? static_cast<int>(n) : 1;
}

/// Memory the system could give this process now without swapping, in bytes (MemAvailable
/// from /proc/meminfo; the physical memory if that cannot be read).
size_t availableMemoryBytes();

/// "1.5 GiB", "300 MiB".
std::string formatBytes(double bytes);

}  // namespace glint
