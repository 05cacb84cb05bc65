#include "glint/scene/medium.h"

#include <algorithm>
#include <cmath>

namespace glint {

double DensityGrid::lookup(const Vec3& p) const {
    if (nx <= 0 || ny <= 0 || nz <= 0) return 0;
    // Voxel centres at i + 0.5: interpolate between the eight around p, 0 beyond the grid.
    const double x = p.x - 0.5, y = p.y - 0.5, z = p.z - 0.5;
    if (!(x > -1 && y > -1 && z > -1 && x < nx && y < ny && z < nz)) return 0;
    const int i = static_cast<int>(std::floor(x)), j = static_cast<int>(std::floor(y)),
              k = static_cast<int>(std::floor(z));
    const double fx = x - i, fy = y - j, fz = z - k;
    auto value = [&](int a, int b, int c) -> double {
        if (a < 0 || b < 0 || c < 0 || a >= nx || b >= ny || c >= nz) return 0;
        return at(a, b, c);
    };
    auto lerp = [](double a, double b, double t) { return a + (b - a) * t; };
    const double c00 = lerp(value(i, j, k), value(i + 1, j, k), fx);
    const double c10 = lerp(value(i, j + 1, k), value(i + 1, j + 1, k), fx);
    const double c01 = lerp(value(i, j, k + 1), value(i + 1, j, k + 1), fx);
    const double c11 = lerp(value(i, j + 1, k + 1), value(i + 1, j + 1, k + 1), fx);
    return lerp(lerp(c00, c10, fy), lerp(c01, c11, fy), fz);
}

float DensityGrid::maxDensity() const {
    float m = 0;
    for (float d : density) m = std::max(m, d);
    return m;
}

}  // namespace glint
