#pragma once
/// Reading environment maps: high-dynamic-range images of linear radiance (Radiance RGBE through
/// stb_image, OpenEXR through the OpenEXR library), for scene/environment.h.

#include <string>
#include <string_view>
#include <vector>

#include "glint/core/input_file.h"

namespace glint {

/// Bytes per texel that reading an environment map and building its EnvironmentMap take at
/// most: the decoded image (a film of doubles for EXR, stb_image's floats for HDR), the float
/// copy the map keeps (12) and its sampling distribution (16). Checked, with the texel count
/// from the file's header, against the memory available before any pixel is decoded.
constexpr double kEnvironmentBytesPerTexel = 56;

/// A linear RGB image in float: width * height * 3 values, row 0 at the top.
struct HdrImage {
    int width = 0, height = 0;
    std::vector<float> rgb;
};

/// Reads the environment map at `path`: a Radiance RGBE file (.hdr, "#?RADIANCE" or "#?RGBE"
/// first) or an OpenEXR file (RGB, or Y for grey), told apart by their first bytes. At most
/// kMaxImageSide texels a side and kMaxImagePixels in all (as images Glint renders), within
/// the memory `limits` allow. Throws RenderError naming the file and the reason: missing or
/// unreadable, not an HDR or EXR image (an 8-bit image is named as such), too large, or
/// malformed.
HdrImage loadEnvironmentImage(const std::string& path, const LoadLimits& limits = {});

/// The same for a file's bytes in memory; `name` is for messages.
HdrImage decodeEnvironmentImage(std::string_view bytes, const std::string& name,
                                const LoadLimits& limits = {});

}  // namespace glint
