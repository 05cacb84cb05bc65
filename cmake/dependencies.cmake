# Third-party libraries, all from Debian 12 packages (see `make deps`).
find_package(Threads REQUIRED)
find_package(PkgConfig REQUIRED)

# CLI11 (libcli11-dev): command-line parsing for apps/.
find_package(CLI11 CONFIG REQUIRED)

# libpng (libpng-dev): PNG encoding in io/ (fast settings).
find_package(PNG REQUIRED)

# stb (libstb-dev): PNG/JPEG decoding in io/ (reference images, textures).
pkg_check_modules(STB REQUIRED IMPORTED_TARGET stb)

# tinyobjloader 2.0rc10 (libtinyobjloader-dev): Wavefront OBJ and MTL parsing in io/, in float
# (Glint stores geometry in float anyway). Its header only: the implementation it carries is
# compiled into glint_core (src/glint/io/tinyobj_impl.cpp).
find_package(tinyobjloader CONFIG REQUIRED)

if(GLINT_BUILD_TESTS)
    # GoogleTest (libgtest-dev, libgmock-dev).
    find_package(GTest REQUIRED)
endif()
