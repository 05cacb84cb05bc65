#pragma once
/// OpenEXR images through the OpenEXR library: linear RGB in 32-bit float, unclamped.

#include <string>
#include <string_view>
#include <utility>

#include "glint/render/film/film.h"

namespace glint {

/// Encodes `film` in memory as a scanline OpenEXR file: channels R, G, B as 32-bit floats,
/// ZIP compressed (lossless), row 0 at the top, every value multiplied by `scale` first.
/// Values are kept as they are, negative ones too; beyond the float range they become +-inf.
///
/// With `aovs` (the film's size), the passes `which` selects are layers of the same file, named
/// as Blender and Nuke show them: albedo.R/G/B, normal.X/Y/Z, depth.Z, variance.R/G/B (the
/// variance times scale^2, so it stays the variance of the scaled colour).
std::string encodeExr(const Film& film, double scale = 1, const RenderPasses* aovs = nullptr,
                      AovSelection which = {});

/// An OpenEXR image with the render passes it holds (empty ones are absent from the file).
struct ExrLayers {
    Film color;
    RenderPasses aovs;   ///< Sized when any pass is there; a missing one is left empty.
    AovSelection found;  ///< Which passes the file held.
};

/// Decodes the beauty image as decodeExr() does, and the layers encodeExr() writes where the
/// file has them (each layer's channels all present, or it counts as absent). Throws RenderError.
ExrLayers decodeExrLayers(std::string_view bytes, const std::string& name);

/// Decodes an OpenEXR file held in `bytes` (scanline or tiled, half, float or uint channels):
/// R, G and B, or Y alone for a grey image. The data window becomes the film, its top-left
/// corner (0, 0). `name` is for messages. Throws RenderError for anything malformed or too
/// large: the same limits as a scene's image size, and the memory available. A crafted header
/// can still make it allocate a film within those limits before the pixel data turns out bad.
Film decodeExr(std::string_view bytes, const std::string& name);

/// The width and height of the data window of the OpenEXR file held in `bytes`, from its header
/// alone (no pixel is decoded), so that callers can check their limits first. Throws
/// RenderError if the header is malformed.
std::pair<long long, long long> exrImageSize(std::string_view bytes, const std::string& name);

}  // namespace glint
