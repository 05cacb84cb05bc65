#pragma once
/// The weights the build embeds: a table that cmake/denoise_weights.cmake generates (or an empty
/// one, builtin_weights_none.cpp, in a build without them). weights.h is the interface.

#include <cstdint>
#include <span>
#include <string_view>

namespace glint::unet {

struct BuiltinWeights {
    std::string_view name;
    const uint8_t* begin;
    const uint8_t* end;
};

std::span<const BuiltinWeights> builtinWeights();

}  // namespace glint::unet
