// The built-in weights of a build without them (cmake/denoise_weights.cmake): none.

#include "glint/denoise/unet/builtin_weights.h"

namespace glint::unet {

std::span<const BuiltinWeights> builtinWeights() { return {}; }

}  // namespace glint::unet
