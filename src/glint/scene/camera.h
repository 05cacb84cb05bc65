#pragma once
/// The pinhole camera of the course: gluLookAt placement and a vertical field of view.

#include <optional>
#include <vector>

#include "glint/core/ray.h"

namespace glint {

/// Camera placement as the scene file gives it.
struct CameraSpec {
    Vec3 eye, center, up;
    double fovyDegrees = 45;  ///< Full vertical field of view, in (0, 180).
    /// Thin lens: radius of the aperture (0: a pinhole, everything sharp) and the distance
    /// along the view direction of the plane in focus (0: the distance from eye to center).
    double apertureRadius = 0;
    double focusDistance = 0;
};

/// The spec at time u (0 to 1) of `keys`, evenly spaced over [0, 1]: eye, center, up, field
/// of view and lens interpolated linearly between the two keys around u.
CameraSpec cameraAt(const std::vector<CameraSpec>& keys, double u);

class Camera {
  public:
    /// A camera for an image of `width` x `height` pixels. The spec must be valid: eye !=
    /// center, up not parallel to the view direction (the scene loader checks this).
    Camera(const CameraSpec& spec, int width, int height);

    /// The ray through image position (x, y), in pixels from the top-left image corner; the
    /// centre of pixel (column j, row i) is (j + 0.5, i + 0.5). Row 0 is the top.
    Ray generateRay(double x, double y) const;
    /// The same through a thin lens: (lensU, lensV) in [0, 1)^2 pick the point on the
    /// aperture. Equal to generateRay(x, y) for a pinhole camera.
    Ray generateRay(double x, double y, double lensU, double lensV) const;
    bool hasLens() const { return apertureRadius_ > 0; }

    /// Where a pinhole camera sees the world point `p`: its image position (x, y) in pixels, as
    /// generateRay takes it, and the factor that turns light leaving `p` towards the eye into
    /// the mean radiance of a pixel around (x, y), for light traced from the lights:
    /// 1 / (A cos^3 theta d^2), A a pixel's area on the image plane at unit distance, theta the
    /// angle off the view direction, d the distance to `p`. Times the cosine at `p` and a flux
    /// density there, it is that pixel's share (pbrt's camera importance We). None behind the
    /// eye; positions outside the image are the caller's to drop.
    struct Projection {
        double x = 0, y = 0;
        double importance = 0;
    };
    std::optional<Projection> project(const Vec3& p) const;
    const Vec3& eye() const { return eye_; }

  private:
    Vec3 eye_, u_, v_, w_;
    double tanHalfX_, tanHalfY_, halfWidth_, halfHeight_;
    double apertureRadius_ = 0, focusDistance_ = 1;
};

}  // namespace glint
