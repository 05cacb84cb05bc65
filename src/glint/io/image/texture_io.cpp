#include "glint/io/image/texture_io.h"

#include <stb_image.h>
#if GLINT_HAVE_WEBP
#include <webp/decode.h>
#endif

#include <climits>
#include <memory>
#include <system_error>

#include "glint/core/error.h"
#include "glint/core/mapped_file.h"
#include "glint/core/system.h"
#include "glint/io/image/image_io.h"

#ifndef GLINT_HAVE_WEBP
#define GLINT_HAVE_WEBP 0
#endif

namespace glint {
namespace {

[[noreturn]] void cannot(const std::string& name, const std::string& why) {
    throw RenderError("cannot read texture '" + name + "': " + why);
}

/// Checks an image's size, read from its header, against the texture limits and the memory
/// that decoding it takes, before any pixel is decoded.
void checkTextureSize(const std::string& name, int w, int h, const LoadLimits& limits) {
    if (w < 1 || h < 1 || w > kMaxTextureSide || h > kMaxTextureSide ||
        static_cast<long long>(w) * h > kMaxTextureTexels)
        cannot(name, "the image is " + std::to_string(w) + " x " + std::to_string(h) +
                         " pixels; textures may have at most " + std::to_string(kMaxTextureSide) +
                         " on a side and " + std::to_string(kMaxTextureTexels) + " in all");
    // Decoding holds the file's own channels and our copy: about 8 bytes per texel at most.
    double needed = static_cast<double>(w) * h * 8;
    if (size_t available = memoryAvailable(limits);
        available > 0 && needed > static_cast<double>(available))
        cannot(name, "decoding it needs about " + formatBytes(needed) + ", more than the " +
                         formatBytes(static_cast<double>(available)) + " available");
}

std::shared_ptr<TextureImage> makeTexture(Image8 img, bool srgb, const std::string& name) {
    auto texture = std::make_shared<TextureImage>();
    texture->width = img.width;
    texture->height = img.height;
    texture->rgb = std::move(img.data);
    texture->srgb = srgb;
    texture->name = name;
    return texture;
}

/// Whether `bytes` begin as a WebP file does: "RIFF", a size, "WEBP".
bool isWebp(std::string_view bytes) {
    return bytes.size() >= 12 && bytes.substr(0, 4) == "RIFF" && bytes.substr(8, 4) == "WEBP";
}

/// w x h pixels, RGBA (or RGB), as a texture, its alpha kept unless opaque everywhere.
std::shared_ptr<TextureImage> fromPixels(const uint8_t* pixels, int w, int h, bool hasAlpha,
                                         bool srgb, const std::string& name) {
    const size_t texels = static_cast<size_t>(w) * h;
    Image8 img{w, h, 3, {}};
    std::vector<uint8_t> alpha;
    if (hasAlpha) {
        img.data.resize(texels * 3);
        alpha.resize(texels);
        bool opaque = true;
        for (size_t i = 0; i < texels; ++i) {
            const uint8_t* p = pixels + i * 4;
            img.data[i * 3] = p[0];
            img.data[i * 3 + 1] = p[1];
            img.data[i * 3 + 2] = p[2];
            alpha[i] = p[3];
            opaque = opaque && p[3] == 255;
        }
        if (opaque) alpha.clear();
    } else {
        img.data.assign(pixels, pixels + texels * 3);
    }
    std::shared_ptr<TextureImage> texture = makeTexture(std::move(img), srgb, name);
    texture->alpha = std::move(alpha);
    return texture;
}

/// A WebP image (lossy or lossless, with or without alpha; animated WebP is refused), its size
/// checked before its pixels are decoded.
std::shared_ptr<TextureImage> decodeWebp(std::string_view bytes, const std::string& name, bool srgb,
                                         const LoadLimits& limits) {
#if GLINT_HAVE_WEBP
    const auto* data = reinterpret_cast<const uint8_t*>(bytes.data());
    WebPBitstreamFeatures features;
    if (WebPGetFeatures(data, bytes.size(), &features) != VP8_STATUS_OK)
        cannot(name, "it is not a valid WebP image");
    if (features.has_animation) cannot(name, "animated WebP images are not read");
    checkTextureSize(name, features.width, features.height, limits);
    const bool hasAlpha = features.has_alpha != 0;
    int w = 0, h = 0;
    std::unique_ptr<uint8_t, void (*)(void*)> pixels(
        hasAlpha ? WebPDecodeRGBA(data, bytes.size(), &w, &h)
                 : WebPDecodeRGB(data, bytes.size(), &w, &h),
        WebPFree);
    if (!pixels || w != features.width || h != features.height)
        cannot(name, "its WebP data is damaged");
    return fromPixels(pixels.get(), w, h, hasAlpha, srgb, name);
#else
    (void)bytes, (void)srgb, (void)limits;
    cannot(name, "this build of Glint (the web page's) does not decode WebP images");
#endif
}

}  // namespace

bool decodesWebp() { return GLINT_HAVE_WEBP != 0; }

std::shared_ptr<TextureImage> loadTextureImage(const std::string& path, bool srgb,
                                               const LoadLimits& limits) {
    std::string problem;
    std::unique_ptr<MappedFile> file = mapInputFile(path, problem);
    if (!file) cannot(path, problem);
    return decodeTextureImage(file->text(), path, srgb, limits);
}

std::shared_ptr<TextureImage> decodeTextureImage(std::string_view bytes, const std::string& name,
                                                 bool srgb, const LoadLimits& limits) {
    if (bytes.empty()) cannot(name, "the image has no bytes");
    if (bytes.size() > static_cast<size_t>(INT_MAX))
        cannot(name, "the image has " + std::to_string(bytes.size()) + " bytes, more than " +
                         std::to_string(INT_MAX));
    if (isWebp(bytes)) return decodeWebp(bytes, name, srgb, limits);
    const auto* data = reinterpret_cast<const stbi_uc*>(bytes.data());
    const int size = static_cast<int>(bytes.size());
    // The header first: a few bytes must not make us allocate gigabytes.
    int w = 0, h = 0, n = 0;
    if (!stbi_info_from_memory(data, size, &w, &h, &n)) cannot(name, stbi_failure_reason());
    checkTextureSize(name, w, h, limits);
    // Images with an alpha channel (grey-alpha, RGBA) keep it, unless it is opaque everywhere.
    const bool hasAlpha = n == 2 || n == 4;
    const int channels = hasAlpha ? 4 : 3;
    std::unique_ptr<stbi_uc, void (*)(void*)> pixels(
        stbi_load_from_memory(data, size, &w, &h, &n, channels), stbi_image_free);
    if (!pixels) cannot(name, stbi_failure_reason());
    return fromPixels(pixels.get(), w, h, hasAlpha, srgb, name);
}

}  // namespace glint
