#include "glint/core/system.h"

#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <string>

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

std::string formatBytes(double bytes) {
    char buf[32];
    if (bytes >= 1 << 30)
        std::snprintf(buf, sizeof buf, "%.1f GiB", bytes / (1 << 30));
    else
        std::snprintf(buf, sizeof buf, "%.0f MiB", bytes / (1 << 20));
    return buf;
}

}  // namespace glint
