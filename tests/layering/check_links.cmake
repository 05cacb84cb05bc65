# Checks that a program or library links none of the libraries that only Glint's modules may
# (core/module.h): OpenVDB and what it brings (TBB, Boost.Iostreams, blosc, log4cplus), which the
# OpenVDB module libglint_vdb.so links instead (src/CMakeLists.txt; docs/performance.md,
# "Start-up"). Run as: cmake -DBINARY=<file> -P check_links.cmake (CTest does, as
# layering.no_openvdb_in_*).
execute_process(COMMAND ldd ${BINARY} OUTPUT_VARIABLE linked RESULT_VARIABLE status)
if(NOT status EQUAL 0)
    message(FATAL_ERROR "ldd ${BINARY} failed (${status})")
endif()
string(REGEX MATCHALL "lib(openvdb|tbb|boost_iostreams|blosc|log4cplus)[^ ]*" heavy "${linked}")
if(heavy)
    message(FATAL_ERROR "${BINARY} links ${heavy}: only the OpenVDB module may")
endif()
string(REGEX MATCHALL "[^ \t\n]+\\.so[^ \t\n]*" all "${linked}")
list(LENGTH all count)
message(STATUS "${BINARY}: ${count} shared libraries, none of OpenVDB's")
