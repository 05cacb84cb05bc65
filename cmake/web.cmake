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
# C++ exceptions are WebAssembly's own (-fwasm-exceptions: Chrome 95, Firefox 100, Safari 15.2,
# Node 17 and later), with the libc++, libc++abi and libunwind variants Debian's frozen cache
# has ("-except"); Emscripten's JavaScript-based ones (GLINT_WEB_WASM_EXCEPTIONS=OFF) route every
# call that may throw through a JavaScript trampoline. setjmp and longjmp (libpng's errors) then
# go through WebAssembly exceptions too (SUPPORT_LONGJMP=wasm, compiler-rt's "wasm-sjlj" variant
# in the cache): Emscripten's JavaScript-based ones cannot share a function with them.
option(GLINT_WEB_WASM_EXCEPTIONS "Web build with WebAssembly exceptions (else JavaScript-based)" ON)
if(GLINT_WEB_WASM_EXCEPTIONS)
    add_compile_options(-msimd128 -fwasm-exceptions -sSUPPORT_LONGJMP=wasm)
    add_link_options(-fwasm-exceptions -sSUPPORT_LONGJMP=wasm)
else()
    add_compile_options(-msimd128 -fexceptions)
    add_link_options(-fexceptions)
endif()
add_library(Threads::Threads INTERFACE IMPORTED)
if(GLINT_WEB_THREADS)
    add_compile_options(-pthread)
    add_link_options(-pthread)
endif()
# With threads, clang 14's catch clauses need libunwind's landing-pad glue replaced
# (web/bindings/wasm_eh_threads.c says why): every program of the threaded build links
# web_eh_glue (web/CMakeLists.txt).
add_library(web_eh_glue INTERFACE)
if(GLINT_WEB_WASM_EXCEPTIONS AND GLINT_WEB_THREADS)
    add_library(web_eh_threads OBJECT ${PROJECT_SOURCE_DIR}/web/bindings/wasm_eh_threads.c)
    target_link_libraries(web_eh_threads PRIVATE glint_options)
    target_link_libraries(web_eh_glue INTERFACE web_eh_threads
                          $<TARGET_OBJECTS:web_eh_threads>)
    target_link_options(web_eh_glue INTERFACE -Wl,--wrap=__cxa_begin_catch)
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
