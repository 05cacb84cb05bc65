#include "glint/io/texture_io.h"

#include <stb_image.h>

#include "glint/core/error.h"
#include "glint/core/system.h"
#include "glint/io/image_io.h"

namespace glint {

std::shared_ptr<TextureImage> loadTextureImage(const std::string& path, bool srgb,
                                               const LoadLimits& limits) {
    auto cannot = [&](const std::string& why) {
        throw RenderError("cannot read texture '" + path + "': " + why);
    };
    if (std::string problem = inputFileProblem(path); !problem.empty()) cannot(problem);
    // The header first: a few bytes must not make us allocate gigabytes.
    int w = 0, h = 0, n = 0;
    if (!stbi_info(path.c_str(), &w, &h, &n)) cannot(stbi_failure_reason());
    if (w < 1 || h < 1 || w > kMaxTextureSide || h > kMaxTextureSide ||
        static_cast<long long>(w) * h > kMaxTextureTexels)
        cannot("the image is " + std::to_string(w) + " x " + std::to_string(h) +
               " pixels; textures may have at most " + std::to_string(kMaxTextureSide) +
               " on a side and " + std::to_string(kMaxTextureTexels) + " in all");
    // Decoding holds the file's own channels and our copy: about 8 bytes per texel at most.
    double needed = static_cast<double>(w) * h * 8;
    if (size_t available = memoryAvailable(limits);
        available > 0 && needed > static_cast<double>(available))
        cannot("decoding it needs about " + formatBytes(needed) + ", more than the " +
               formatBytes(static_cast<double>(available)) + " available");
    Image8 img = readImage8(path, 3);
    auto texture = std::make_shared<TextureImage>();
    texture->width = img.width;
    texture->height = img.height;
    texture->rgb = std::move(img.data);
    texture->srgb = srgb;
    texture->name = path;
    return texture;
}

}  // namespace glint
