#include "glint/core/input_file.h"

#include <sys/stat.h>

#include <cerrno>
#include <cstring>
#include <system_error>

#include "glint/core/system.h"

namespace glint {

std::string inputFileProblem(const std::string& path, long long maxBytes) {
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0) return std::strerror(errno);
    if (S_ISDIR(st.st_mode)) return "it is a directory";
    if (!S_ISREG(st.st_mode)) return "not a regular file";
    if (st.st_size > maxBytes)
        return "the file has " + std::to_string(st.st_size) + " bytes, more than the limit of " +
               std::to_string(maxBytes);
    return {};
}

size_t memoryAvailable(const LoadLimits& limits) {
    return limits.memoryBytes ? limits.memoryBytes : availableMemoryBytes();
}

std::unique_ptr<MappedFile> mapInputFile(const std::string& path, std::string& problem) {
    problem = inputFileProblem(path);
    if (!problem.empty()) return nullptr;
    try {
        return std::make_unique<MappedFile>(path);
    } catch (const std::system_error& e) {
        problem = e.code().message();
        return nullptr;
    }
}

}  // namespace glint
