# Compiler warnings and floating-point settings shared by every Glint target.
add_library(glint_options INTERFACE)
target_compile_options(glint_options INTERFACE
    -Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wno-sign-conversion
    # Images must not depend on whether the compiler fuses a*b+c: keep IEEE rounding per operation.
    -ffp-contract=off)
if(GLINT_WERROR)
    target_compile_options(glint_options INTERFACE -Werror)
endif()
