#pragma once
/// Textures for the diffuse colour: images (bilinear, repeat or clamp) and a procedural checker.
/// A material names one by id (Material::texture); its value replaces the material's diffuse
/// colour at the hit (docs/scene-format.md, "Textures").

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "glint/math/vec3.h"

namespace glint {

/// An 8-bit RGB image as read from a file, kept 8-bit (3 bytes per texel) and decoded to linear
/// values on lookup. Row 0 is the top of the image, where v = 1.
struct TextureImage {
    int width = 0, height = 0;
    std::vector<uint8_t> rgb;  ///< width * height * 3 bytes.
    /// Alpha bytes (width * height, linear, 255 opaque) of images that have an alpha channel
    /// that is not everywhere 255; empty: opaque.
    std::vector<uint8_t> alpha;
    /// The bytes are sRGB-encoded (PNG and JPEG files nearly always are) and are decoded to
    /// linear values; false: they are linear already (value / 255).
    bool srgb = true;
    std::string name;  ///< Where it came from, for messages.

    /// Linear value of texel (x, y), 0 <= x < width, 0 <= y < height.
    Vec3 texel(int x, int y) const;
    /// Alpha of texel (x, y) in [0, 1]; 1 for images without alpha.
    double alphaTexel(int x, int y) const {
        return alpha.empty() ? 1.0 : alpha[static_cast<size_t>(y) * width + x] * (1 / 255.0);
    }
    /// Mean linear value over all texels.
    Vec3 average() const;
};

/// What lookups outside [0, 1] see.
enum class TextureWrap : uint8_t {
    Repeat,          ///< The image tiles the plane.
    Clamp,           ///< Coordinates are clamped to [0, 1]: the edge texels stretch outwards.
    MirroredRepeat,  ///< The image tiles the plane, every other tile mirrored (glTF, OpenGL).
};

/// A filtered texture value with its alpha.
struct Rgba {
    Vec3 rgb;
    double a = 1;
};

/// The linear value of `image` at (u, v), bilinearly filtered between the four nearest texel
/// centres. u runs left to right, v bottom to top. Non-finite coordinates read as 0.
Vec3 sampleBilinear(const TextureImage& image, double u, double v, TextureWrap wrap);

/// As sampleBilinear, with a wrap mode per axis (u: `wrapS`, v: `wrapT`), and alpha.
Rgba sampleBilinearRgba(const TextureImage& image, double u, double v, TextureWrap wrapS,
                        TextureWrap wrapT);

/// The decoded linear value of an sRGB-encoded byte (IEC 61966-2-1).
double srgbToLinear(uint8_t byte);

struct Texture {
    enum class Kind : uint8_t { Image, Checker };
    Kind kind = Kind::Checker;
    TextureWrap wrap = TextureWrap::Repeat;
    std::shared_ptr<const TextureImage> image;  ///< Kind::Image only.
    /// Image: a tint multiplying the image (an MTL's Kd); checker: the colour of the cell at
    /// the origin...
    Vec3 a{1};
    /// ...and checker: the other cells' colour.
    Vec3 b{0};
    /// Checker: the side of one square, in texture-coordinate units on surfaces that have
    /// them, else in world units.
    double scale = 1;

    /// The diffuse colour at a hit at world-space `p`, with texture coordinates (u, v) when
    /// `hasUv`. An image needs texture coordinates: without them it gives `fallback`.
    Vec3 eval(bool hasUv, double u, double v, const Vec3& p, const Vec3& fallback) const;
};

/// Parity (0 or 1) of the checker cell holding coordinate x for squares of side `scale`: the
/// cell [k scale, (k + 1) scale) has parity k mod 2. Exact for any finite x, however large.
int checkerParity(double x, double scale);

}  // namespace glint
