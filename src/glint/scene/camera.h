#pragma once
/// The pinhole camera of the course: gluLookAt placement and a vertical field of view.

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

  private:
    Vec3 eye_, u_, v_, w_;
    double tanHalfX_, tanHalfY_, halfWidth_, halfHeight_;
    double apertureRadius_ = 0, focusDistance_ = 1;
};

}  // namespace glint
