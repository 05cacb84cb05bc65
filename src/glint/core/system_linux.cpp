// The system queries of core/system.h on Linux (and other Unix systems): /proc and sysconf; and
// core/module.h's shared modules: dlopen.

#include <dlfcn.h>
#include <unistd.h>

#include <fstream>
#include <mutex>
#include <string>
#include <vector>

#include "glint/core/module.h"
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

namespace {

/// The folder of the file this code was loaded from (the program, or the shared library the
/// Python module is), with a trailing slash; empty if it cannot be told.
std::string ownFolder() {
    Dl_info info{};
    if (!::dladdr(reinterpret_cast<void*>(&loadModule), &info) || !info.dli_fname) return {};
    const std::string path = info.dli_fname;
    const size_t slash = path.rfind('/');
    return slash == std::string::npos ? std::string("./") : path.substr(0, slash + 1);
}

}  // namespace

LoadedModule loadModule(const std::string& fileName, const std::string& buildDir,
                        std::string* error) {
    // dlopen keeps one copy of a file however often it is opened; the lock keeps the messages
    // of threads that ask at once apart.
    static std::mutex mutex;
    std::lock_guard lock(mutex);
    const std::string own = ownFolder();
    std::vector<std::string> places;
    if (!own.empty()) {
        places.push_back(own + fileName);
        places.push_back(own + "../lib/glint/" + fileName);
    }
    if (!buildDir.empty() && buildDir + "/" != own) places.push_back(buildDir + "/" + fileName);
    std::string why;
    for (const std::string& path : places) {
        if (::access(path.c_str(), F_OK) != 0) {
            why += (why.empty() ? "" : "; ") + path + ": not there";
            continue;
        }
        if (void* handle = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL)) return {handle};
        const char* message = ::dlerror();
        why += (why.empty() ? "" : "; ") + std::string(message ? message : path + ": not loaded");
    }
    if (error) *error = why.empty() ? "no folder to look in" : why;
    return {};
}

void* moduleSymbol(const LoadedModule& module, const char* name) {
    return module.handle ? ::dlsym(module.handle, name) : nullptr;
}

}  // namespace glint
