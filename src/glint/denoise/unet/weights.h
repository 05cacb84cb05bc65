#pragma once
/// The network denoiser's weights by name: Open Image Denoise's published archives
/// (denoise-weights/README.md), "rt_hdr_alb_nrm" for rt_hdr_alb_nrm.tza. The native build embeds
/// those denoise-weights/fetch.sh fetched (cmake/denoise_weights.cmake); a build without them,
/// and the web build, whose page fetches them, has them only as registered at run time.

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace glint {

/// The archive `name`: registered at run time, else built in; empty if neither.
std::span<const uint8_t> denoiserWeights(std::string_view name);

/// Makes `bytes` the archive `name` from now on (in place of a built-in one of that name).
void registerDenoiserWeights(std::string name, std::vector<uint8_t> bytes);

/// The names of the archives built in (none in a build without them).
std::vector<std::string> builtinDenoiserWeights();

}  // namespace glint
