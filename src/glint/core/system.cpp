#include "glint/core/system.h"

#include <cstdio>
#include <string>

namespace glint {

// availableMemoryBytes() is the platform's: system_linux.cpp (natively) or system_web.cpp
// (WebAssembly).

std::string formatBytes(double bytes) {
    char buf[32];
    if (bytes >= 1 << 30)
        std::snprintf(buf, sizeof buf, "%.1f GiB", bytes / (1 << 30));
    else
        std::snprintf(buf, sizeof buf, "%.0f MiB", bytes / (1 << 20));
    return buf;
}

}  // namespace glint
