/* stb_image's implementation from Debian's libstb-dev header, for the web build (natively,
   Glint links Debian's libstb.so, built from the same header). */
#define STB_IMAGE_IMPLEMENTATION
#include <stb_image.h>
