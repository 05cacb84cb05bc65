#include "glint/scene/camera.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "glint/math/sampling.h"

namespace glint {

Camera::Camera(const CameraSpec& spec, int width, int height) : eye_(spec.eye) {
    // The orthonormal frame of gluLookAt: w points back from the view direction.
    w_ = normalize(spec.eye - spec.center);
    u_ = normalize(cross(spec.up, w_));
    v_ = cross(w_, u_);
    halfWidth_ = static_cast<double>(width) / 2;
    halfHeight_ = static_cast<double>(height) / 2;
    tanHalfY_ = std::tan(spec.fovyDegrees * std::numbers::pi / 360);
    tanHalfX_ = tanHalfY_ * static_cast<double>(width) / static_cast<double>(height);
    apertureRadius_ = spec.apertureRadius;
    focusDistance_ = spec.focusDistance > 0 ? spec.focusDistance : length(spec.center - spec.eye);
}

CameraSpec cameraAt(const std::vector<CameraSpec>& keys, double u) {
    if (keys.size() < 2) return keys.empty() ? CameraSpec{} : keys.front();
    const double at = std::clamp(u, 0.0, 1.0) * static_cast<double>(keys.size() - 1);
    const size_t k = std::min(static_cast<size_t>(at), keys.size() - 2);
    const double s = at - static_cast<double>(k);
    const CameraSpec &a = keys[k], &b = keys[k + 1];
    auto mix = [s](auto x, auto y) { return x * (1 - s) + y * s; };
    CameraSpec c = a;
    c.eye = mix(a.eye, b.eye);
    c.center = mix(a.center, b.center);
    c.up = mix(a.up, b.up);
    c.fovyDegrees = mix(a.fovyDegrees, b.fovyDegrees);
    c.apertureRadius = mix(a.apertureRadius, b.apertureRadius);
    c.focusDistance = mix(a.focusDistance, b.focusDistance);
    return c;
}

Ray Camera::generateRay(double x, double y) const {
    double alpha = tanHalfX_ * (x - halfWidth_) / halfWidth_;
    double beta = tanHalfY_ * (halfHeight_ - y) / halfHeight_;
    return Ray{eye_, normalize(u_ * alpha + v_ * beta - w_), 0, kInfinity};
}

std::optional<Camera::Projection> Camera::project(const Vec3& p) const {
    const Vec3 d = p - eye_;
    const double z = -dot(d, w_);  // along the view direction
    const double d2 = dot(d, d);
    if (!(z > 0) || !(d2 > 0)) return std::nullopt;
    const double alpha = dot(d, u_) / z, beta = dot(d, v_) / z;
    Projection out;
    out.x = halfWidth_ + alpha * halfWidth_ / tanHalfX_;
    out.y = halfHeight_ - beta * halfHeight_ / tanHalfY_;
    const double cosTheta = z / std::sqrt(d2);
    const double pixelArea = (tanHalfX_ / halfWidth_) * (tanHalfY_ / halfHeight_);
    out.importance = 1 / (pixelArea * cosTheta * cosTheta * cosTheta * d2);
    return out;
}

}  // namespace glint

namespace glint {

Ray Camera::generateRay(double x, double y, double lensU, double lensV) const {
    Ray pinhole = generateRay(x, y);
    if (!hasLens()) return pinhole;
    // Every ray through pixel (x, y) meets the pinhole ray on the plane in focus, which lies
    // focusDistance in front of the eye along -w.
    Vec3 focus = pinhole.at(focusDistance_ / dot(pinhole.dir, -w_));
    auto [lx, ly] = sampleUniformDisk(lensU, lensV);
    Vec3 origin = eye_ + (u_ * lx + v_ * ly) * apertureRadius_;
    return Ray{origin, normalize(focus - origin), 0, kInfinity};
}

}  // namespace glint
