// The system queries of core/system.h on Linux (and other Unix systems): /proc and sysconf.

#include <unistd.h>

#include <fstream>
#include <string>

#include "glint/core/system.h"

namespace glint {

size_t availableMemoryBytes() {
    std::ifstream in("/proc/meminfo");
    std::string key;
    size_t value = 0;
    std::string unit;
    while (in >> key >> value >> unit)
        if (key == "MemAvailable:") return value * 1024;
    long pages = ::sysconf(_SC_PHYS_PAGES), page = ::sysconf(_SC_PAGE_SIZE);
    return pages > 0 && page > 0 ? static_cast<size_t>(pages) * static_cast<size_t>(page) : 0;
}

}  // namespace glint
