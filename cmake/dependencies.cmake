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
