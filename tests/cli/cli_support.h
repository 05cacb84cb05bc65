#pragma once
// Runs the glint binary as a user would and captures what it prints.

#include <string>

namespace glint::test {

struct CommandResult {
    int exitCode = -1;
    std::string out;  ///< stdout
    std::string err;  ///< stderr
};

/// Runs `glint <args>` through the shell in `workDir` (created if missing). `args` is shell
/// text: quote paths with spaces yourself.
CommandResult runGlint(const std::string& args, const std::string& workDir);

/// Runs `imgdiff <args>` the same way.
CommandResult runImgdiff(const std::string& args, const std::string& workDir);

/// Writes `text` to `path`, creating directories as needed.
void writeFile(const std::string& path, const std::string& text);

/// A fresh, empty directory under the system's temporary directory, unique to this test; removed
/// when the test program ends, unless a test failed.
std::string freshDir(const std::string& name);

/// The bytes of the file at `path` (empty if it cannot be read).
std::string readBytes(const std::string& path);

/// Whether `needle` occurs in `haystack`.
bool contains(const std::string& haystack, const std::string& needle);

}  // namespace glint::test
