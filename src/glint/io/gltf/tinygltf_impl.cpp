// tinygltf's implementation, which libtinygltf-dev ships in its header behind
// TINYGLTF_IMPLEMENTATION, compiled into glint_core rather than linked from the package's shared
// library (as for tinyobjloader, see tinyobj_impl.cpp): no dynamic-linking cost per run, the
// sanitizer and fuzzing builds instrument it, and it is built with Glint's settings
// (glint/io/gltf/tinygltf.h) against Debian's nlohmann/json header. Compiled without Glint's
// warnings (src/CMakeLists.txt): it is not our code.
#define TINYGLTF_IMPLEMENTATION
// tinygltf 2.7's glTF writer uses std::ofstream even when TINYGLTF_NO_FS leaves <fstream> out.
#include <fstream>

#include "glint/io/gltf/tinygltf.h"
