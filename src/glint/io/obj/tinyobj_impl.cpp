// tinyobjloader's implementation, which libtinyobjloader-dev ships in its header behind
// TINYOBJLOADER_IMPLEMENTATION, compiled into glint_core instead of linked from the package's
// shared library: every run of glint then starts without the dynamic linker searching one more
// library for each symbol (about a million instructions per process, measured with callgrind
// on scene7), and the sanitizer and fuzzing builds instrument the OBJ parser like Glint's own
// code. Compiled without Glint's warnings (src/CMakeLists.txt): it is not our code.
#define TINYOBJLOADER_IMPLEMENTATION
#include <tiny_obj_loader.h>
