# Compiler warnings and floating-point settings shared by every Glint target.
add_library(glint_options INTERFACE)
target_compile_options(glint_options INTERFACE
    -Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wno-sign-conversion
    # Images must not depend on whether the compiler fuses a*b+c: keep IEEE rounding per operation.
    -ffp-contract=off)
if(GLINT_WERROR)
    target_compile_options(glint_options INTERFACE -Werror)
endif()

# Sanitizers (make test-sanitize): applied to every target through glint_options, and to the
# libraries' own objects through the global flags so that nothing is left uninstrumented.
if(GLINT_SANITIZE)
    message(STATUS "Sanitizers: ${GLINT_SANITIZE}")
    add_compile_options(-fsanitize=${GLINT_SANITIZE} -fno-omit-frame-pointer
                        -fno-sanitize-recover=all)
    add_link_options(-fsanitize=${GLINT_SANITIZE})
    # GCC 12's -Wmaybe-uninitialized misfires on instrumented code: libstdc++'s <regex>, used by
    # the CLI tests, fails -Werror in RelWithDebInfo sanitizer builds. Normal builds keep it.
    if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
        target_compile_options(glint_options INTERFACE -Wno-maybe-uninitialized)
    endif()
endif()
