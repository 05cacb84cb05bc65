#include "glint/scene/studio_environment.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

namespace glint {
namespace {

constexpr double kPi = std::numbers::pi;

double smoothstep(double e0, double e1, double x) {
    double t = std::clamp((x - e0) / (e1 - e0), 0.0, 1.0);
    return t * t * (3 - 2 * t);
}

/// A rectangle of uniform radiance, infinitely far away, facing the origin: the directions
/// whose gnomonic projection onto the plane through `centre` lands within +-halfWidth across
/// and +-halfHeight up (tangents of the half angles), with edges feathered over +-feather.
struct Softbox {
    Vec3 centre;  ///< Unit direction towards the box's middle.
    double halfWidth, halfHeight, feather;
    double radiance;

    double eval(const Vec3& d) const {
        double c = dot(d, centre);
        if (c <= 0) return 0;
        // Across: horizontal and perpendicular to the centre; up: perpendicular to both.
        Vec3 across = normalize(cross(Vec3(0, 1, 0), centre));
        Vec3 up = cross(centre, across);
        double u = std::abs(dot(d, across)) / c, v = std::abs(dot(d, up)) / c;
        return radiance * (1 - smoothstep(halfWidth - feather, halfWidth + feather, u)) *
               (1 - smoothstep(halfHeight - feather, halfHeight + feather, v));
    }
};

/// The softboxes, as the header describes them (+z is towards a framed model's camera).
const Softbox kSoftboxes[] = {
    {normalize(Vec3(-1.0, 1.25, 1.0)), 0.42, 0.30, 0.06, 5.0},  // key: upper left, in front
    {normalize(Vec3(1.3, 0.35, 0.8)), 0.30, 0.24, 0.06, 1.5},   // fill: low on the right
    {normalize(Vec3(0.25, 1.1, -1.0)), 0.75, 0.10, 0.04, 3.5},  // rim: a strip above, behind
};

/// The dome: grey, brighter towards the zenith; the ground half lighter near the horizon.
double dome(double y) {
    double sky = 0.30 + 0.15 * std::max(y, 0.0);
    double ground = 0.55 - 0.10 * std::min(std::max(-y, 0.0), 1.0);
    double t = smoothstep(-0.05, 0.05, y);  // about +-3 degrees around the horizon
    return ground + (sky - ground) * t;
}

}  // namespace

Vec3 studioRadiance(const Vec3& dir) {
    double L = dome(dir.y);
    for (const Softbox& box : kSoftboxes) L += box.eval(dir);
    return Vec3(L);
}

std::shared_ptr<const EnvironmentMap> studioEnvironment() {
    static const std::shared_ptr<const EnvironmentMap> map = [] {
        std::vector<float> rgb(static_cast<size_t>(kStudioWidth) * kStudioHeight * 3);
        for (int y = 0; y < kStudioHeight; ++y) {
            // The texel centre's direction, as EnvironmentMap maps it (rotation 0).
            double theta = kPi * (y + 0.5) / kStudioHeight;
            for (int x = 0; x < kStudioWidth; ++x) {
                double phi = 2 * kPi * (x + 0.5) / kStudioWidth - kPi;
                Vec3 d(std::sin(theta) * std::cos(phi), std::cos(theta),
                       std::sin(theta) * std::sin(phi));
                Vec3 L = studioRadiance(d);
                float* p = &rgb[(static_cast<size_t>(y) * kStudioWidth + x) * 3];
                p[0] = static_cast<float>(L.x);
                p[1] = static_cast<float>(L.y);
                p[2] = static_cast<float>(L.z);
            }
        }
        return std::make_shared<const EnvironmentMap>(kStudioWidth, kStudioHeight, std::move(rgb));
    }();
    return map;
}

}  // namespace glint
