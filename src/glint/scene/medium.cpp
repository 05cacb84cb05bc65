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

MajorantGrid::MajorantGrid(const DensityGrid& grid) {
    constexpr int B = kBlock;
    nx = (grid.nx + B - 1) / B;
    ny = (grid.ny + B - 1) / B;
    nz = (grid.nz + B - 1) / B;
    bound.assign(static_cast<size_t>(nx) * ny * nz, 0.0f);
    // Each voxel raises the bound of every block whose interpolation reaches it: voxel i is
    // read anywhere in [i - 0.5, i + 1.5], so by blocks floor((i - 1) / B) to floor((i + 1) / B).
    auto blocks = [](int i, int n, int& lo, int& hi) {
        lo = std::max(0, (i - 1) / B - (i - 1 < 0));
        hi = std::min(n - 1, (i + 1) / B);
    };
    for (int k = 0; k < grid.nz; ++k) {
        int c0, c1;
        blocks(k, nz, c0, c1);
        for (int j = 0; j < grid.ny; ++j) {
            int b0, b1;
            blocks(j, ny, b0, b1);
            for (int i = 0; i < grid.nx; ++i) {
                const float d = grid.at(i, j, k);
                if (!(d > 0)) continue;
                int a0, a1;
                blocks(i, nx, a0, a1);
                for (int c = c0; c <= c1; ++c)
                    for (int b = b0; b <= b1; ++b)
                        for (int a = a0; a <= a1; ++a) {
                            float& m = bound[(static_cast<size_t>(c) * ny + b) * nx + a];
                            m = std::max(m, d);
                        }
            }
        }
    }
}

float DensityGrid::maxDensity() const {
    float m = 0;
    for (float d : density) m = std::max(m, d);
    return m;
}

}  // namespace glint
