# The web build (make web, docs/web.md): Glint's library compiled with Debian's Emscripten, in
# place of cmake/dependencies.cmake. Configure with emcmake:
#   emcmake cmake -S . -B build-web/mt -DGLINT_WEB_DEBIAN_SOURCES=build-web/debian
# The same targets as natively, from what Emscripten can use:
#   - header-only libraries from their Debian packages (stb, tinyobjloader, tinygltf,
#     nlohmann/json), through a directory of links to just those headers (never /usr/include
#     itself, whose glibc headers are not Emscripten's);
#   - zlib and libpng compiled from their Debian source packages (web/tools/debian-sources.sh
#     fetches them), so that PNG files are byte for byte the native build's;
#   - OpenEXR, Draco and meshopt are not available: src/CMakeLists.txt links stand-ins.

enable_language(C)

option(GLINT_WEB_THREADS "Web build with threads (pthreads in Web Workers; needs cross-origin isolation)" ON)
set(GLINT_WEB_DEBIAN_SOURCES "" CACHE PATH "Where web/tools/debian-sources.sh unpacked zlib and libpng")
if(NOT EXISTS "${GLINT_WEB_DEBIAN_SOURCES}/zlib/zlib.h" OR
   NOT EXISTS "${GLINT_WEB_DEBIAN_SOURCES}/libpng/png.h")
    message(FATAL_ERROR "GLINT_WEB_DEBIAN_SOURCES must name the folder web/tools/debian-sources.sh "
                        "filled (zlib/ and libpng/); got '${GLINT_WEB_DEBIAN_SOURCES}'")
endif()

# Both builds use WebAssembly SIMD (every current browser has it); the threaded one also
# pthreads, which every object of the program must be compiled for (shared memory, atomics).
# C++ exceptions are Emscripten's JavaScript-based ones. WebAssembly's own (-fwasm-exceptions)
# measured 5-10% faster in Node and within the noise in Chromium, but clang 14's catch clauses
# with threads address libunwind's thread-local landing-pad context as a plain global, so they
# would need libunwind's glue replaced (docs/performance.md): not worth it.
add_compile_options(-msimd128 -fexceptions)
add_link_options(-fexceptions)
add_library(Threads::Threads INTERFACE IMPORTED)
if(GLINT_WEB_THREADS)
    add_compile_options(-pthread)
    add_link_options(-pthread)
endif()
message(STATUS "Glint web build: ${CMAKE_CXX_COMPILER}, threads ${GLINT_WEB_THREADS}")

# Header-only Debian packages, each header linked into one folder.
set(web_include ${CMAKE_BINARY_DIR}/debian-headers)
file(MAKE_DIRECTORY ${web_include})
foreach(header tiny_obj_loader.h tiny_gltf.h nlohmann)
    if(NOT EXISTS /usr/include/${header})
        message(FATAL_ERROR "/usr/include/${header} is missing: make deps installs it")
    endif()
    file(CREATE_LINK /usr/include/${header} ${web_include}/${header} SYMBOLIC)
endforeach()
foreach(lib tinyobjloader::tinyobjloader TinyGLTF::TinyGLTF nlohmann_json::nlohmann_json)
    add_library(${lib} INTERFACE IMPORTED)
    set_target_properties(${lib} PROPERTIES INTERFACE_INCLUDE_DIRECTORIES ${web_include})
endforeach()

# stb_image: natively Debian's libstb.so; here its header's implementation, compiled once.
add_library(web_stb STATIC ${PROJECT_SOURCE_DIR}/web/bindings/stb_image_impl.c)
target_include_directories(web_stb SYSTEM PUBLIC /usr/include/stb)
target_compile_options(web_stb PRIVATE -w)
add_library(PkgConfig::STB ALIAS web_stb)

# zlib and libpng from Debian's sources, as Debian builds them for amd64 (zlib with
# -DUNALIGNED_OK; libpng with its prebuilt configuration).
set(zlib_dir ${GLINT_WEB_DEBIAN_SOURCES}/zlib)
add_library(web_zlib STATIC
    ${zlib_dir}/adler32.c ${zlib_dir}/compress.c ${zlib_dir}/crc32.c ${zlib_dir}/deflate.c
    ${zlib_dir}/infback.c ${zlib_dir}/inffast.c ${zlib_dir}/inflate.c ${zlib_dir}/inftrees.c
    ${zlib_dir}/trees.c ${zlib_dir}/uncompr.c ${zlib_dir}/zutil.c)
target_include_directories(web_zlib SYSTEM PUBLIC ${zlib_dir})
target_compile_definitions(web_zlib PRIVATE UNALIGNED_OK HAVE_UNISTD_H)
target_compile_options(web_zlib PRIVATE -O3 -w)

set(png_dir ${GLINT_WEB_DEBIAN_SOURCES}/libpng)
set(png_config ${CMAKE_BINARY_DIR}/libpng-config)
configure_file(${png_dir}/scripts/pnglibconf.h.prebuilt ${png_config}/pnglibconf.h COPYONLY)
add_library(web_png STATIC
    ${png_dir}/png.c ${png_dir}/pngerror.c ${png_dir}/pngget.c ${png_dir}/pngmem.c
    ${png_dir}/pngpread.c ${png_dir}/pngread.c ${png_dir}/pngrio.c ${png_dir}/pngrtran.c
    ${png_dir}/pngrutil.c ${png_dir}/pngset.c ${png_dir}/pngtrans.c ${png_dir}/pngwio.c
    ${png_dir}/pngwrite.c ${png_dir}/pngwtran.c ${png_dir}/pngwutil.c)
target_include_directories(web_png SYSTEM PUBLIC ${png_dir} ${png_config})
target_compile_definitions(web_png PRIVATE PNG_ARM_NEON_OPT=0 PNG_INTEL_SSE_OPT=0)
target_compile_options(web_png PRIVATE -O3 -w)
target_link_libraries(web_png PUBLIC web_zlib)
add_library(PNG::PNG ALIAS web_png)
