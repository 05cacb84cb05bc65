#include "glint/io/image/image_io.h"

#include <png.h>
#include <stb_image.h>

#include <algorithm>
#include <bit>
#include <cctype>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <memory>
#include <sstream>

#include "glint/core/atomic_file.h"
#include "glint/core/error.h"
#include "glint/io/image/exr.h"
#include "glint/math/bits.h"

namespace glint {

std::optional<ImageFormat> imageFormatFor(const std::string& path) {
    auto dot = path.find_last_of('.');
    if (dot == std::string::npos || path.find('/', dot) != std::string::npos) return std::nullopt;
    std::string ext = path.substr(dot + 1);
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (ext == "png") return ImageFormat::Png;
    if (ext == "ppm") return ImageFormat::Ppm;
    if (ext == "pfm") return ImageFormat::Pfm;
    if (ext == "exr") return ImageFormat::Exr;
    return std::nullopt;
}

namespace {

/// "MAGIC\nW H\nLAST\n", the header of PPM and PFM files.
std::string header(const char* magic, int w, int h, const char* last) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "%s\n%d %d\n%s\n", magic, w, h, last);
    return buf;
}

}  // namespace

/// PNG through libpng, tuned for speed: zlib level 1 and the "up" filter. On renders this is
/// about 4x faster than stb's encoder and the files come out smaller (docs/performance.md).
std::string encodePng(const Image8& img) {
    std::string out;
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
    png_infop info = png ? png_create_info_struct(png) : nullptr;
    if (!info) {
        png_destroy_write_struct(&png, nullptr);
        throw RenderError("PNG encoding failed: out of memory");
    }
    if (setjmp(png_jmpbuf(png))) {  // libpng reports errors by longjmp
        png_destroy_write_struct(&png, &info);
        throw RenderError("PNG encoding failed");
    }
    png_set_write_fn(
        png, &out,
        [](png_structp p, png_bytep data, png_size_t n) {
            static_cast<std::string*>(png_get_io_ptr(p))->append(reinterpret_cast<char*>(data), n);
        },
        nullptr);
    png_set_IHDR(png, info, static_cast<png_uint_32>(img.width),
                 static_cast<png_uint_32>(img.height), 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_set_compression_level(png, 1);
    png_set_filter(png, 0, PNG_FILTER_UP);
    png_write_info(png, info);
    for (int y = 0; y < img.height; ++y)
        png_write_row(png, img.data.data() + static_cast<size_t>(y) * img.width * 3);
    png_write_end(png, nullptr);
    png_destroy_write_struct(&png, &info);
    return out;
}

std::string encodeImage(const Film& film, ImageFormat format, const DisplayTransform& display,
                        const RenderPasses* aovs, AovSelection which) {
    const int w = film.width(), h = film.height();
    const double scale = display.scale();
    std::string out;
    if (format == ImageFormat::Exr) return encodeExr(film, scale, aovs, which);
    if (aovs && which.any())
        throw RenderError("render passes (--aov) are layers of an OpenEXR file: write .exr");
    if (format == ImageFormat::Pfm) {
        // Little-endian floats (negative scale), rows from the bottom of the image up.
        out = header("PF", w, h, "-1.0");
        size_t header = out.size();
        out.resize(header + static_cast<size_t>(w) * h * 12);
        char* p = out.data() + header;
        for (int y = h - 1; y >= 0; --y)
            for (int x = 0; x < w; ++x) {
                const Vec3& c = film.at(x, y);
                float rgb[3] = {static_cast<float>(scale * c.x), static_cast<float>(scale * c.y),
                                static_cast<float>(scale * c.z)};
                static_assert(std::endian::native == std::endian::little);
                std::memcpy(p, rgb, 12);
                p += 12;
            }
        return out;
    }
    Image8 img = toImage8(film, display);
    if (format == ImageFormat::Ppm) {
        out = header("P6", w, h, "255");
        out.append(reinterpret_cast<const char*>(img.data.data()), img.data.size());
        return out;
    }
    return encodePng(img);
}

void writeImage(const std::string& path, const Film& film, const DisplayTransform& display,
                const RenderPasses* aovs, AovSelection which) {
    std::optional<ImageFormat> format = imageFormatFor(path);
    if (!format)
        throw RenderError("cannot write '" + path + "': unknown image format (use " +
                          kImageExtensions + ")");
    writeFileAtomically(path, encodeImage(film, *format, display, aovs, which));
}

Image8 readImage8(const std::string& path, int channels) {
    int w = 0, h = 0, n = 0;
    if (!stbi_info(path.c_str(), &w, &h, &n))
        throw RenderError("cannot read image '" + path + "': " + stbi_failure_reason());
    int want = channels ? channels : (n <= 2 ? 1 : 3);
    std::unique_ptr<stbi_uc, void (*)(void*)> pixels(stbi_load(path.c_str(), &w, &h, &n, want),
                                                     stbi_image_free);
    if (!pixels) throw RenderError("cannot read image '" + path + "': " + stbi_failure_reason());
    Image8 img{w, h, want, {}};
    img.data.assign(pixels.get(), pixels.get() + static_cast<size_t>(w) * h * want);
    return img;
}

Film readPfm(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw RenderError("cannot read image '" + path + "': cannot open file");
    std::string magic;
    int w = 0, h = 0;
    double scale = 0;
    in >> magic >> w >> h >> scale;
    in.get();  // the single whitespace byte before the data
    int channels = magic == "PF" ? 3 : (magic == "Pf" ? 1 : 0);
    if (!in || channels == 0 || w <= 0 || h <= 0 || scale == 0 || w > (1 << 16) || h > (1 << 16))
        throw RenderError("cannot read image '" + path + "': not a PFM file");
    // Check the data is there before allocating for it: the header is not to be trusted.
    auto start = in.tellg();
    in.seekg(0, std::ios::end);
    auto available = in.tellg() - start;
    in.seekg(start);
    size_t bytes = static_cast<size_t>(w) * h * channels * 4;
    if (start < 0 || available < 0 || static_cast<size_t>(available) < bytes)
        throw RenderError("cannot read image '" + path + "': file is truncated");
    std::vector<float> data(static_cast<size_t>(w) * h * channels);
    in.read(reinterpret_cast<char*>(data.data()), static_cast<std::streamsize>(data.size() * 4));
    if (!in) throw RenderError("cannot read image '" + path + "': file is truncated");
    bool bigEndian = scale > 0;
    if (bigEndian != (std::endian::native == std::endian::big))
        for (float& f : data) f = bitCast<float>(__builtin_bswap32(bitCast<uint32_t>(f)));
    Film film(w, h);
    size_t i = 0;
    for (int y = h - 1; y >= 0; --y)
        for (int x = 0; x < w; ++x, i += channels)
            film.at(x, y) = channels == 3 ? Vec3(data[i], data[i + 1], data[i + 2]) : Vec3(data[i]);
    return film;
}

namespace {

std::string readExrBytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw RenderError("cannot read image '" + path + "': cannot open file");
    std::string bytes;
    in.seekg(0, std::ios::end);
    bytes.resize(static_cast<size_t>(std::max<std::streamoff>(0, in.tellg())));
    in.seekg(0);
    if (!in.read(bytes.data(), static_cast<std::streamsize>(bytes.size())))
        throw RenderError("cannot read image '" + path + "': read failed");
    return bytes;
}

}  // namespace

Film readExr(const std::string& path) { return decodeExr(readExrBytes(path), path); }

ExrLayers readExrLayers(const std::string& path) {
    return decodeExrLayers(readExrBytes(path), path);
}

}  // namespace glint
