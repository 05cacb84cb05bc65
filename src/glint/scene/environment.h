#pragma once
/// An environment map: radiance arriving from infinitely far away in every direction, given by
/// an equirectangular (latitude-longitude) image of linear RGB radiance, and importance-sampled
/// by luminance over solid angle for the path tracer. The scene layer holds the pixels; reading
/// them from a file is io/'s business (io/image/environment_io.h).
///
/// Mapping (the same as Blender/Cycles' equirectangular Environment Texture, once Blender's
/// z-up axes are turned into Glint's y-up ones as the OBJ importer does: Blender (x, y, z) =
/// Glint (x, -z, y)). For a unit world direction d = (x, y, z) and rotation 0:
///
///     s = 1/2 + atan2(z, x) / (2 pi)     horizontal image coordinate, 0 at the left edge
///     t = theta / pi, theta = acos(y)     vertical image coordinate, 0 at the top edge
///
/// and conversely d = (sin theta cos phi, cos theta, sin theta sin phi) with theta = pi t and
/// phi = 2 pi s - pi. So the top row is straight up (+y), the bottom row straight down, the
/// middle row the horizon; the image's centre looks along +x, its left and right edges along
/// -x, the column at s = 1/4 along -z (Blender's +y, "forward" in a y-up OBJ file) and s = 3/4
/// along +z. Cycles computes u = (pi - atan2(by, bx)) / (2 pi) and v = 1 - acos(bz) / pi
/// (v up from the bottom row) for a Blender direction b: the same texel.
///
/// Rotation: `rotationDegrees` turns the environment about +y by that angle, right-handed
/// (counter-clockwise seen from above), as `rotate 0 1 0 angle` turns an object: what the
/// unrotated map shows in direction d is seen in direction R_y(angle) d. In Blender that is a
/// Mapping node of type Point with rotation Z = -angle on the Environment Texture's vector (or
/// of type Texture with Z = +angle).

#include <optional>
#include <vector>

#include "glint/math/distribution.h"
#include "glint/math/sampling.h"
#include "glint/math/vec3.h"

namespace glint {

/// An equirectangular environment map (see the file comment for its mapping and rotation).
///
/// Lookups are **bilinear** between the four nearest texel centres (as Cycles' default Linear
/// interpolation), wrapping around horizontally and clamped at the top and bottom rows.
///
/// Sampling draws a texel (Distribution2D: a row by its marginal, then a column within it), in
/// proportion to the mean luminance of the bilinear radiance over the texel's cell times the
/// cell's solid angle (luminance x sin(theta), integrated over the row), then a direction
/// uniformly over the cell's solid angle (phi uniform across the column, cos(theta) across the
/// row). The density over solid angle is thus constant over each cell: its probability over its
/// solid angle, proportional to its luminance; 1 / (4 pi) everywhere for a constant map, and
/// finite at the poles. Every direction where eval() can be nonzero has nonzero density (the
/// cell's mean includes its neighbours' share of the interpolation), so estimates are unbiased.
/// Immutable once built; every method may be called from any thread.
class EnvironmentMap {
  public:
    /// `width` x `height` texels of linear RGB radiance (rgb holds width * height * 3 floats,
    /// row 0 at the top, looking up, as equirectangular images are stored), multiplied by
    /// `scale` (finite, >= 0) on lookup, and rotated by `rotationDegrees` (finite) about +y.
    /// Texels that are NaN or negative read as 0, those above kMaxRadiance as kMaxRadiance.
    /// Throws std::invalid_argument for sizes below 1x1, an rgb of the wrong size, or a scale
    /// or rotation out of range.
    EnvironmentMap(int width, int height, std::vector<float> rgb, double scale = 1,
                   double rotationDegrees = 0);

    int width() const { return width_; }
    int height() const { return height_; }
    double scale() const { return scale_; }
    double rotationDegrees() const { return rotationDegrees_; }

    /// Radiance arriving from unit world direction `dir` (pointing towards the map): bilinear
    /// between texels, times the scale.
    Vec3 eval(const Vec3& dir) const;

    /// A direction drawn by sample(): the unit world direction towards the map, the radiance
    /// arriving along it (eval(wi), exactly) and its density over solid angle (pdf(wi),
    /// exactly).
    struct Sample {
        Vec3 wi;
        Vec3 L;
        double pdf = 0;
    };
    /// A direction towards the map drawn with `u` in [0, 1)^2, importance-sampled as the class
    /// comment says. None only where rounding puts the direction in a neighbouring texel of
    /// density 0. The radiance may be 0 (a black map, or scale 0).
    std::optional<Sample> sample(Point2 u) const;

    /// The density over solid angle (1 / sr) of sample() at unit direction `dir`.
    double pdf(const Vec3& dir) const;

    /// Mean radiance over the sphere of directions (per solid angle) of eval(): exactly the
    /// mean of the bilinear radiance, times the scale. A constant map gives its constant.
    Vec3 averageRadiance() const { return average_ * scale_; }

    /// Power for choosing between lights (pbrt-v4's Phi of an image infinite light): the
    /// luminance flux through a disk of radius `sceneRadius` (the scene's bounding sphere)
    /// from every direction, pi r^2 x 4 pi x luminance(averageRadiance()).
    double power(double sceneRadius) const;

    /// The image coordinates (s right, t down, each in [0, 1]) that the direction `dir` (not
    /// necessarily unit, not zero) looks at, rotation included: s in [0, 1), t = 0 straight up.
    Point2 imageCoordinates(const Vec3& dir) const;
    /// The unit world direction that image coordinates (s, t) look in, rotation included.
    Vec3 direction(Point2 st) const;

    /// Texel (x, y) as stored (after clamping, before the scale); 0 <= x < width, 0 <= y < height.
    Vec3 texel(int x, int y) const {
        const float* p = &rgb_[(static_cast<size_t>(y) * width_ + x) * 3];
        return {p[0], p[1], p[2]};
    }

    /// eval() and pdf() at image coordinates (s, t) (as imageCoordinates() gives them, the
    /// rotation included): what they return for a direction that looks there, without the
    /// trigonometry of finding where it looks.
    Vec3 evalAt(Point2 st) const;
    double pdfAt(Point2 st) const;

  private:
    int width_, height_;
    std::vector<float> rgb_;
    double scale_, rotationDegrees_;
    double rotationTurns_;       ///< rotationDegrees / 360, added to s on lookup.
    std::vector<double> bands_;  ///< Per row: its solid angle over 2 pi, cos(theta0) - cos(theta1).
    Distribution2D distribution_;
    Vec3 average_;  ///< Mean over the sphere, before the scale.
};

}  // namespace glint
