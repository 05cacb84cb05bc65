#pragma once
/// Image files: PNG and PPM (8-bit, clamped like the course), PFM and OpenEXR (32-bit float,
/// linear, unclamped).

#include <optional>
#include <string>

#include "glint/io/image/exr.h"
#include "glint/render/film/display.h"
#include "glint/render/film/film.h"

namespace glint {

enum class ImageFormat { Png, Ppm, Pfm, Exr };

/// The extensions Glint writes, for messages: ".png, .ppm, .pfm or .exr".
inline constexpr const char* kImageExtensions = ".png, .ppm, .pfm or .exr";

/// The format a file name asks for by its extension (case-insensitive), if Glint writes it.
std::optional<ImageFormat> imageFormatFor(const std::string& path);

/// True for the formats that store floats (PFM, EXR): no clamping, no sRGB curve.
inline bool isFloatFormat(ImageFormat f) { return f == ImageFormat::Pfm || f == ImageFormat::Exr; }

/// Writes `film` atomically in the format of `path`'s extension, through `display` (see
/// encodeImage). Throws RenderError.
void writeImage(const std::string& path, const Film& film, const DisplayTransform& display = {},
                const RenderPasses* aovs = nullptr, AovSelection which = {});

/// Encodes `film` in memory in `format`. 8-bit formats take the whole display transform
/// (exposure, then the course's floor(255 c) or the sRGB curve); float formats take the
/// exposure only, as a scale, and ignore `display.srgb`: they always hold linear values.
/// The passes `which` selects of `aovs` are layers of an OpenEXR file (exr.h); other formats
/// have no layers: asking for any there throws RenderError.
std::string encodeImage(const Film& film, ImageFormat format, const DisplayTransform& display = {},
                        const RenderPasses* aovs = nullptr, AovSelection which = {});

/// Reads an 8-bit image (PNG, JPEG, PPM/PGM). `channels` 0 keeps the file's channel count
/// (1 or 3; alpha is dropped), 1 or 3 converts. Throws RenderError.
Image8 readImage8(const std::string& path, int channels = 0);

/// Reads a PFM file (colour "PF" or grey "Pf", either byte order). Throws RenderError.
Film readPfm(const std::string& path);

/// Reads an OpenEXR file (RGB or Y; see decodeExr in exr.h). Throws RenderError.
Film readExr(const std::string& path);

/// Reads an OpenEXR file with the render passes it holds (decodeExrLayers in exr.h). Throws
/// RenderError.
ExrLayers readExrLayers(const std::string& path);

}  // namespace glint
