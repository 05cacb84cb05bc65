#pragma once
/// Image files: PNG and PPM (8-bit, clamped like the course) and PFM (32-bit float, linear).

#include <optional>
#include <string>

#include "glint/render/film.h"

namespace glint {

enum class ImageFormat { Png, Ppm, Pfm };

/// The format a file name asks for by its extension (case-insensitive), if Glint writes it.
std::optional<ImageFormat> imageFormatFor(const std::string& path);

/// Writes `film` atomically in the format of `path`'s extension. Throws RenderError.
void writeImage(const std::string& path, const Film& film);

/// Encodes `film` in memory in `format`.
std::string encodeImage(const Film& film, ImageFormat format);

/// Reads an 8-bit image (PNG, JPEG, PPM/PGM). `channels` 0 keeps the file's channel count
/// (1 or 3; alpha is dropped), 1 or 3 converts. Throws RenderError.
Image8 readImage8(const std::string& path, int channels = 0);

/// Reads a PFM file (colour "PF" or grey "Pf", either byte order). Throws RenderError.
Film readPfm(const std::string& path);

}  // namespace glint
