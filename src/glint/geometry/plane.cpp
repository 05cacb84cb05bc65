#include "glint/geometry/plane.h"

#include <cmath>

namespace glint {

std::optional<Plane> Plane::make(const Vec3& point, const Vec3& normal,
                                 const Transform& worldFromObject) {
    Vec3 n = worldFromObject.normal(normal);
    // Scaled first: a normal of huge or tiny components would overflow or underflow as
    // its length is computed.
    double big = maxComponent(abs(n));
    if (!(big > 0) || !std::isfinite(big)) return std::nullopt;
    n = n / big;
    double len = length(n);
    return Plane{worldFromObject.point(point), n / len};
}

}  // namespace glint
