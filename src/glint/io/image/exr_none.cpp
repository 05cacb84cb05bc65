// The web build's stand-in for exr.cpp: Emscripten has no OpenEXR, so EXR files (images written,
// environment maps read) are refused with a message.

#include "glint/core/error.h"
#include "glint/io/image/exr.h"

namespace glint {
namespace {

[[noreturn]] void unavailable(const std::string& what) {
    throw RenderError(what +
                      ": OpenEXR files are not available in the web build of Glint (the "
                      "command-line glint reads and writes them; use .hdr or .png)");
}

}  // namespace

std::string encodeExr(const Film&, double, const RenderPasses*, AovSelection) {
    unavailable("cannot write EXR");
}

ExrLayers decodeExrLayers(std::string_view, const std::string& name) {
    unavailable("cannot read '" + name + "'");
}

Film decodeExr(std::string_view, const std::string& name) {
    unavailable("cannot read '" + name + "'");
}

std::pair<long long, long long> exrImageSize(std::string_view, const std::string& name) {
    unavailable("cannot read '" + name + "'");
}

}  // namespace glint
