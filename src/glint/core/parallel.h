#pragma once
/// Thread counts.

#include <thread>

namespace glint {

/// The number of threads the machine runs at once (at least 1): what "all threads" means.
inline int hardwareThreads() {
    unsigned n = std::thread::hardware_concurrency();
    return n ? static_cast<int>(n) : 1;
}

}  // namespace glint
