# Third-party libraries, all from Debian 12 packages (see `make deps`).
find_package(Threads REQUIRED)
find_package(PkgConfig REQUIRED)

# CLI11 (libcli11-dev): command-line parsing for apps/.
find_package(CLI11 CONFIG REQUIRED)

# libpng (libpng-dev): PNG encoding in io/ (fast settings).
find_package(PNG REQUIRED)

# OpenEXR 3.1 (libopenexr-dev, with Imath from libimath-dev): EXR reading and writing in io/.
# Debian's Imath config notes that the Python binding's library (python3-imath) is missing:
# a status line only, Glint does not use it.
find_package(OpenEXR CONFIG REQUIRED)
message(STATUS "OpenEXR ${OpenEXR_VERSION}: .exr output")

# stb (libstb-dev): PNG/JPEG decoding in io/ (reference images, textures).
pkg_check_modules(STB REQUIRED IMPORTED_TARGET stb)

# libwebp 1.2 (libwebp-dev): WebP textures in io/ (glTF's EXT_texture_webp; texture_io.cpp).
# The web build has none: it refuses WebP images with a message.
pkg_check_modules(WEBP REQUIRED IMPORTED_TARGET libwebp)

# tinyobjloader 2.0rc10 (libtinyobjloader-dev): Wavefront OBJ and MTL parsing in io/, in float
# (Glint stores geometry in float anyway). Its header only: the implementation it carries is
# compiled into glint_io (src/glint/io/obj/tinyobj_impl.cpp).
find_package(tinyobjloader CONFIG REQUIRED)

# tinygltf 2.7 (libtinygltf-dev) with nlohmann/json 3.11 (nlohmann-json3-dev): glTF 2.0 (.gltf,
# .glb) in io/. Like tinyobjloader, only the header: its implementation is compiled into
# glint_io (src/glint/io/gltf/tinygltf_impl.cpp) against the JSON package's header, and images are
# decoded by Glint's own texture reader (stb_image), so Debian's libtinygltf.so is not linked.
find_package(TinyGLTF CONFIG REQUIRED)
find_package(nlohmann_json 3 CONFIG REQUIRED)

# Draco 1.5.5 (libdraco-dev) and meshoptimizer 0.18 (libmeshoptimizer-dev): the decoders of
# compressed glTF meshes (KHR_draco_mesh_compression; EXT_ and KHR_meshopt_compression), in io/
# (src/glint/io/gltf/gltf_compression.cpp, gltf_draco.cpp), both as Debian's shared libraries
# (src/CMakeLists.txt says why not libdraco.a).
find_package(draco CONFIG REQUIRED)
find_package(meshoptimizer CONFIG REQUIRED)

# OpenVDB 10 (libopenvdb-dev): the density grids of heterogeneous media, read in io/
# (src/glint/io/vdb/vdb_reader.cpp, built as a module of its own) into a dense copy. Debian ships no CMake config for it but
# its find module, FindOpenVDB.cmake, in a folder of its own that joins the module path only
# here (beside it are find modules for OpenEXR and TBB that must not replace the others). That
# module requires Boost.Iostreams (libboost-iostreams-dev, whose headers OpenVDB's need too),
# which libopenvdb-dev does not pull in. It also sets BUILD_SHARED_LIBS and Boost_* variables in
# the caller's scope: hence the function. GLINT_OPENVDB=OFF builds vdb_reader_none.cpp instead,
# which refuses .vdb files with a message (the web build always does). Only the OpenVDB module
# (libglint_vdb.so, src/CMakeLists.txt) links it, loaded the first time a .vdb file is read:
# Debian's libopenvdb links log4cplus 2.0, which starts a few idle threads of its own when it is
# loaded, and TBB, Boost.Iostreams and blosc, which cost every run that linked them 0.03 s.
option(GLINT_OPENVDB "Read OpenVDB density grids (libopenvdb-dev, libboost-iostreams-dev)" ON)
function(glint_find_openvdb)
    find_path(GLINT_OPENVDB_MODULE_DIR FindOpenVDB.cmake
              PATHS /usr/lib/${CMAKE_LIBRARY_ARCHITECTURE}/cmake/OpenVDB
                    /usr/local/lib/cmake/OpenVDB /usr/lib/cmake/OpenVDB)
    find_package(Boost QUIET COMPONENTS iostreams)
    if(NOT GLINT_OPENVDB_MODULE_DIR OR NOT Boost_FOUND)
        message(FATAL_ERROR "OpenVDB not found (FindOpenVDB.cmake: '${GLINT_OPENVDB_MODULE_DIR}'; "
                            "Boost.Iostreams found: ${Boost_FOUND}). Debian: apt-get install "
                            "libopenvdb-dev libboost-iostreams-dev (or `make deps`); or configure "
                            "with -DGLINT_OPENVDB=OFF to build Glint without .vdb files")
    endif()
    # TBB's own config first, all its targets at once: the OpenVDB module's FindTBB defines
    # TBB::tbb alone, and Embree's config (the benchmarks', bench/) then fails on a half-defined
    # export set.
    find_package(TBB CONFIG QUIET)
    list(PREPEND CMAKE_MODULE_PATH ${GLINT_OPENVDB_MODULE_DIR})
    find_package(OpenVDB REQUIRED COMPONENTS openvdb)
    message(STATUS "OpenVDB ${OpenVDB_VERSION}: .vdb density grids")
endfunction()
if(GLINT_OPENVDB)
    glint_find_openvdb()
else()
    message(STATUS "GLINT_OPENVDB=OFF: .vdb files are refused (vdb_reader_none.cpp)")
endif()

# Open MPI 4.1 (openmpi-bin, libopenmpi-dev): glint-mpi, glint across the ranks of an MPI job
# (apps/glint_mpi.cpp, docs/scale-out.md), and its tests. Optional: without MPI the rest of
# Glint builds as before, without glint-mpi. GLINT_MPI=OFF leaves it out even when MPI is found.
option(GLINT_MPI "Build glint-mpi when MPI is found" ON)
if(GLINT_MPI)
    find_package(MPI COMPONENTS CXX)
endif()
if(MPI_CXX_FOUND)
    message(STATUS "MPI ${MPI_CXX_VERSION} (${MPIEXEC_EXECUTABLE}): building glint-mpi")
elseif(GLINT_MPI)
    message(STATUS "MPI not found: glint-mpi and its tests are not built (Debian: apt-get install "
                   "openmpi-bin libopenmpi-dev, or `make deps`)")
else()
    message(STATUS "GLINT_MPI=OFF: glint-mpi and its tests are not built")
endif()

if(GLINT_BUILD_TESTS)
    # GoogleTest (libgtest-dev, libgmock-dev).
    find_package(GTest REQUIRED)
endif()
