#pragma once
/// Reading texture images (PNG, JPEG and the other 8-bit formats stb_image decodes; WebP through
/// libwebp, natively).

#include <memory>
#include <string>
#include <string_view>

#include "glint/core/input_file.h"
#include "glint/scene/texture.h"

namespace glint {

/// Largest texture side and texel count Glint reads.
constexpr int kMaxTextureSide = 32768;
constexpr long long kMaxTextureTexels = 1LL << 28;

/// Reads the image at `path` as 8-bit RGB (grey is expanded, alpha dropped, 16-bit reduced),
/// sRGB-encoded unless `srgb` is false. The size is checked against the limits above and the
/// memory available before the pixels are decoded. Throws RenderError with the reason.
std::shared_ptr<TextureImage> loadTextureImage(const std::string& path, bool srgb = true,
                                               const LoadLimits& limits = {});

/// The same for an image file's bytes in memory (a glTF's embedded images); `name` says where
/// they came from, in messages and in TextureImage::name. Throws RenderError with the reason.
std::shared_ptr<TextureImage> decodeTextureImage(std::string_view bytes, const std::string& name,
                                                 bool srgb = true, const LoadLimits& limits = {});

/// Whether this build decodes WebP images (the native one does; the web build does not).
bool decodesWebp();

}  // namespace glint
