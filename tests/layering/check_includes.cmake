# Checks that no file under src/glint includes upward: a file in one layer may include only its
# own layer and the ones below, in this order (docs/design.md, "Layers"):
#   math < core < geometry < accel < scene < render < denoise < io
# and within render/, its sub-folders below the renderer's driver at its top:
#   render/bsdfs < render/lights < render/film < render/integrators < render
# (bsdfs, lights and film know nothing of one another's types either way; the order only
# forbids the lower ones to reach up.)
# Run as: cmake -DSRC=<repo>/src/glint -P check_includes.cmake (CTest does, as layering.includes).
set(layers math core geometry accel scene render/bsdfs render/lights render/film
    render/integrators render denoise io)
# The layer of a path under src/glint: its first folder, or render/SUB for render's sub-folders.
function(layer_of path out)
    if(path MATCHES "^render/(bsdfs|lights|film|integrators)/")
        set(${out} "render/${CMAKE_MATCH_1}" PARENT_SCOPE)
    else()
        string(REGEX MATCH "^[a-z]+" first "${path}")
        set(${out} "${first}" PARENT_SCOPE)
    endif()
endfunction()
file(GLOB_RECURSE files RELATIVE ${SRC} ${SRC}/*.h ${SRC}/*.cpp ${SRC}/*.inl)
set(problems "")
foreach(f IN LISTS files)
    layer_of("${f}" layer)
    list(FIND layers "${layer}" rank)
    if(rank LESS 0)
        string(APPEND problems "  ${f}: in no known layer\n")
        continue()
    endif()
    file(STRINGS ${SRC}/${f} includes REGEX "^#include \"glint/")
    foreach(line IN LISTS includes)
        string(REGEX MATCH "glint/([a-z_/]+)\\.[a-z]+\"" _ "${line}")
        layer_of("${CMAKE_MATCH_1}" included)
        list(FIND layers "${included}" target)
        if(target GREATER rank)
            string(APPEND problems "  ${f} (${layer}) includes ${included}: ${line}\n")
        endif()
    endforeach()
endforeach()
list(LENGTH files count)
if(problems)
    message(FATAL_ERROR "Upward includes (the layers are ${layers}):\n${problems}")
endif()
message(STATUS "${count} files, no upward include")
