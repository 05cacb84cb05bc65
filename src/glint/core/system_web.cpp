// The system queries of core/system.h in WebAssembly (Emscripten): the memory a module may still
// take is what its heap may grow to (-sMAXIMUM_MEMORY) less what malloc holds now. And
// core/module.h: the web build loads no shared modules.

#include <emscripten/heap.h>
#include <malloc.h>

#include "glint/core/module.h"
#include "glint/core/system.h"

namespace glint {

size_t availableMemoryBytes() {
    const size_t most = emscripten_get_heap_max();
    const size_t used = static_cast<size_t>(mallinfo().uordblks);
    return most > used ? most - used : 0;
}

LoadedModule loadModule(const std::string& fileName, const std::string&, std::string* error) {
    if (error) *error = "the web build loads no modules (" + fileName + ")";
    return {};
}

void* moduleSymbol(const LoadedModule&, const char*) { return nullptr; }

}  // namespace glint
