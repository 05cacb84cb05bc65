#pragma once
/// Shared modules loaded at run time, for the heavy libraries that most runs never need: a run
/// pays for loading a module (and the libraries it links: their relocations and static
/// constructors) only the first time it needs one (docs/performance.md, "Start-up"). Platform
/// code: dlopen on Linux (system_linux.cpp); the web build has no modules (system_web.cpp).

#include <string>

namespace glint {

/// A loaded module: its symbols can be looked up. Modules stay loaded until the process ends.
struct LoadedModule {
    void* handle = nullptr;
};

/// Loads the module file `fileName` (for example "libglint_vdb.so"), looked for where Glint's
/// own code was loaded from (the glint program's folder, the Python module's), then in
/// `../lib/glint` from there, then in `buildDir` (the build tree's folder, for programs run
/// from their build tree, such as the tests). The same file is loaded once however often it is
/// asked for. On failure: a handle of null, and in `error` where it looked and why each failed.
LoadedModule loadModule(const std::string& fileName, const std::string& buildDir,
                        std::string* error);

/// The address of the symbol `name` the module exports; null if it exports none.
void* moduleSymbol(const LoadedModule& module, const char* name);

}  // namespace glint
