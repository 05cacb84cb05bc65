# Precompiled headers: the standard library headers that most Glint files include (directly or
# through Glint's own headers), compiled once per target rather than once per file.
# With GCC 12 in C++20 they cost about 1 s of each file's compile, a third of a typical file;
# the precompiled header costs about 3 s once per target. It only puts standard headers first:
# no Glint file defines a macro before its first include (tinyobj_impl.cpp and tinygltf_impl.cpp
# define their libraries' macros, which these headers do not read). Of the glint program's 108
# objects, 98 came out byte for byte the same as without it; the others differ in the order of
# their template instantiations and, in a few functions that build error messages, in inlining.
# Glint's own headers and the third-party ones stay out, so changing one rebuilds only the
# files that include it. GLINT_PCH=OFF compiles without (e.g. to check that every file includes
# what it uses).
option(GLINT_PCH "Precompile the standard headers common to Glint's files" ON)
set(GLINT_PCH_HEADERS
    <algorithm> <array> <bit> <cmath> <cstdint> <cstdio> <cstring> <limits> <memory> <numbers>
    <optional> <stdexcept> <string> <string_view> <system_error> <utility> <vector>
    <atomic> <chrono> <functional> <map> <mutex> <set> <sstream> <unordered_map> <variant>)

# Gives `target` the precompiled header (each target needs its own: they differ in flags).
function(glint_precompile_headers target)
    if(GLINT_PCH)
        target_precompile_headers(${target} PRIVATE ${GLINT_PCH_HEADERS})
    endif()
endfunction()
