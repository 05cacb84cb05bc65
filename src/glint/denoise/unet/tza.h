#pragma once
/// Open Image Denoise's tensor archives (.tza): the file format its published weights come in
/// (docs/denoiser-method.md). An archive is a table of named tensors: each a shape, a layout
/// ("oihw" for a convolution's weights, "x" for a bias) and 32- or 16-bit floats. This reader is
/// Glint's own, from the format as OIDN's weights files lay it out (version 2):
///
///     u16 magic 0x41D7, u8 major version 2, u8 minor version, u64 offset of the table
///     table: u32 count, then per tensor: u16 name length, the name, u8 dimensions, u32 each
///            dimension, a layout letter per dimension, a type letter ('f' float32, 'h'
///            float16), u64 offset of its data (little-endian throughout)
///
/// Every count, offset and size is checked against the bytes before anything is read, so a
/// truncated or corrupt archive is an error that says why, never a read past its end.

#include <cstdint>
#include <map>
#include <span>
#include <string>
#include <vector>

namespace glint {

/// One tensor of an archive, its values as floats (16-bit ones widened exactly).
struct TzaTensor {
    std::vector<int> dims;  ///< Outermost first: o, i, h, w for "oihw".
    std::string layout;     ///< A letter per dimension.
    std::vector<float> values;

    size_t size() const { return values.size(); }
};

/// The tensors of an archive, by name.
using TzaTensors = std::map<std::string, TzaTensor>;

/// Reads the archive in `bytes`. Throws std::runtime_error("NAME: why") for anything that is not
/// a well-formed archive of version 2, `name` standing for where the bytes came from.
TzaTensors parseTza(std::span<const uint8_t> bytes, const std::string& name);

/// Reads the archive file at `path` (parseTza's errors, or that it cannot be read).
TzaTensors readTza(const std::string& path);

/// The float a 16-bit IEEE 754 half has (subnormals, infinities and NaN included).
float halfToFloat(uint16_t h);

}  // namespace glint
