#include "glint/io/image/environment_io.h"

#include <stb_image.h>

#include <climits>
#include <memory>
#include <system_error>

#include "glint/core/error.h"
#include "glint/core/mapped_file.h"
#include "glint/core/system.h"
#include "glint/io/image/exr.h"
#include "glint/scene/scene.h"

namespace glint {
namespace {

[[noreturn]] void cannot(const std::string& name, const std::string& why) {
    throw RenderError("cannot read environment map '" + name + "': " + why);
}

/// Checks the size from an image's header against Glint's image limits and the memory that
/// reading and sampling it take, before any pixel is decoded.
void checkSize(const std::string& name, long long w, long long h, const LoadLimits& limits) {
    if (w < 1 || h < 1 || w > kMaxImageSide || h > kMaxImageSide || w * h > kMaxImagePixels)
        cannot(name, "the image is " + std::to_string(w) + " x " + std::to_string(h) +
                         " pixels; environment maps may have at most " +
                         std::to_string(kMaxImageSide) + " on a side and " +
                         std::to_string(kMaxImagePixels) + " in all");
    double needed = static_cast<double>(w) * static_cast<double>(h) * kEnvironmentBytesPerTexel;
    if (size_t available = memoryAvailable(limits);
        available > 0 && needed > static_cast<double>(available))
        cannot(name, "reading and sampling it needs about " + formatBytes(needed) +
                         ", more than the " + formatBytes(static_cast<double>(available)) +
                         " available");
}

constexpr std::string_view kExrMagic = "\x76\x2f\x31\x01";

HdrImage decodeRgbe(std::string_view bytes, const std::string& name, const LoadLimits& limits) {
    const auto* data = reinterpret_cast<const stbi_uc*>(bytes.data());
    const int size = static_cast<int>(bytes.size());
    int w = 0, h = 0, n = 0;
    if (!stbi_info_from_memory(data, size, &w, &h, &n))
        cannot(name, std::string("not a valid Radiance HDR file (") + stbi_failure_reason() + ")");
    checkSize(name, w, h, limits);
    std::unique_ptr<float, void (*)(void*)> pixels(
        stbi_loadf_from_memory(data, size, &w, &h, &n, 3), stbi_image_free);
    if (!pixels)
        cannot(name, std::string("not a valid Radiance HDR file (") + stbi_failure_reason() + ")");
    HdrImage img{w, h, {}};
    img.rgb.assign(pixels.get(), pixels.get() + static_cast<size_t>(w) * h * 3);
    return img;
}

HdrImage decodeOpenExr(std::string_view bytes, const std::string& name, const LoadLimits& limits) {
    auto [w, h] = exrImageSize(bytes, name);
    checkSize(name, w, h, limits);
    HdrImage img{static_cast<int>(w), static_cast<int>(h), {}};
    Film film = decodeExr(bytes, name);  // throws "cannot read image 'name': why"
    img.rgb.resize(static_cast<size_t>(img.width) * static_cast<size_t>(img.height) * 3);
    float* p = img.rgb.data();
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x, p += 3) {
            const Vec3& c = film.at(x, y);
            p[0] = static_cast<float>(c.x);
            p[1] = static_cast<float>(c.y);
            p[2] = static_cast<float>(c.z);
        }
    return img;
}

}  // namespace

HdrImage loadEnvironmentImage(const std::string& path, const LoadLimits& limits) {
    std::string problem;
    std::unique_ptr<MappedFile> file = mapInputFile(path, problem);
    if (!file) cannot(path, problem);
    return decodeEnvironmentImage(file->text(), path, limits);
}

HdrImage decodeEnvironmentImage(std::string_view bytes, const std::string& name,
                                const LoadLimits& limits) {
    if (bytes.empty()) cannot(name, "the file is empty");
    if (bytes.size() > static_cast<size_t>(INT_MAX))
        cannot(name, "the file has " + std::to_string(bytes.size()) + " bytes, more than " +
                         std::to_string(INT_MAX));
    if (bytes.starts_with(kExrMagic)) return decodeOpenExr(bytes, name, limits);
    const auto* data = reinterpret_cast<const stbi_uc*>(bytes.data());
    const int size = static_cast<int>(bytes.size());
    if (bytes.starts_with("#?") && stbi_is_hdr_from_memory(data, size))
        return decodeRgbe(bytes, name, limits);
    int w = 0, h = 0, n = 0;
    if (stbi_info_from_memory(data, size, &w, &h, &n))
        cannot(name,
               "it is an 8-bit image, not a high-dynamic-range one: environment maps are Radiance "
               "HDR (.hdr) or OpenEXR (.exr) files");
    cannot(name, "not a Radiance HDR (.hdr) or OpenEXR (.exr) file");
}

}  // namespace glint
