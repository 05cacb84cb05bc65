// Writes a procedural smoke plume as an OpenVDB file of one float grid named "density", for
// the docs' and the benchmark's media scenes (docs/scene-format.md, "Media"):
//     glint_make_smoke_vdb smoke.vdb [resolution]
// A column 1 unit wide and 1.5 high standing on y = 0, centred on x = z = 0, that widens as it
// rises, its density broken up by a few octaves of value noise (a hash of the lattice points,
// so the file is the same on every machine). Voxels of density below 0.01 stay inactive.

#include <openvdb/openvdb.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace {

/// A value in [0, 1) for the lattice point (x, y, z).
double lattice(int x, int y, int z) {
    uint64_t h = static_cast<uint64_t>(x) * 0x9E3779B97F4A7C15ULL ^
                 static_cast<uint64_t>(y) * 0xC2B2AE3D27D4EB4FULL ^
                 static_cast<uint64_t>(z) * 0x165667B19E3779F9ULL;
    h ^= h >> 33;
    h *= 0xFF51AFD7ED558CCDULL;
    h ^= h >> 33;
    return static_cast<double>(h >> 11) * 0x1p-53;
}

/// Trilinearly interpolated lattice noise, smoothed, in [0, 1).
double noise(double x, double y, double z) {
    const int i = static_cast<int>(std::floor(x)), j = static_cast<int>(std::floor(y)),
              k = static_cast<int>(std::floor(z));
    auto s = [](double t) { return t * t * (3 - 2 * t); };
    const double fx = s(x - i), fy = s(y - j), fz = s(z - k);
    auto lerp = [](double a, double b, double t) { return a + (b - a) * t; };
    auto at = [&](int a, int b, int c) { return lattice(i + a, j + b, k + c); };
    return lerp(lerp(lerp(at(0, 0, 0), at(1, 0, 0), fx), lerp(at(0, 1, 0), at(1, 1, 0), fx), fy),
                lerp(lerp(at(0, 0, 1), at(1, 0, 1), fx), lerp(at(0, 1, 1), at(1, 1, 1), fx), fy),
                fz);
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: glint_make_smoke_vdb OUT.vdb [resolution]\n");
        return 1;
    }
    const int n = argc > 2 ? std::max(8, std::atoi(argv[2])) : 64;  // voxels across 1 unit
    openvdb::initialize();
    openvdb::FloatGrid::Ptr grid = openvdb::FloatGrid::create(0);
    grid->setName("density");
    const double voxel = 1.0 / n;
    grid->setTransform(openvdb::math::Transform::createLinearTransform(voxel));
    auto acc = grid->getAccessor();
    const int height = n * 3 / 2;
    for (int y = 0; y < height; ++y) {
        const double h = (y + 0.5) * voxel;  // height in units
        const double radius = 0.15 + 0.25 * h / 1.5;
        for (int x = -n / 2; x < n / 2; ++x)
            for (int z = -n / 2; z < n / 2; ++z) {
                const double px = (x + 0.5) * voxel, pz = (z + 0.5) * voxel;
                // Swirl: the column leans and twists as it rises.
                const double cx = 0.08 * std::sin(h * 4), cz = 0.08 * std::cos(h * 3);
                const double r = std::hypot(px - cx, pz - cz) / radius;
                if (r >= 1) continue;
                double turbulence = 0, amplitude = 0.5, frequency = 6;
                for (int octave = 0; octave < 4; ++octave) {
                    turbulence +=
                        amplitude * noise(px * frequency, h * frequency - h * 2, pz * frequency);
                    amplitude *= 0.5;
                    frequency *= 2;
                }
                const double falloff = (1 - r * r) * std::min(1.0, h * 8) * (1 - h / 1.6);
                const double d = std::max(0.0, falloff * (1.6 * turbulence - 0.35)) * 3;
                if (d >= 0.01) acc.setValue(openvdb::Coord(x, y, z), static_cast<float>(d));
            }
    }
    openvdb::io::File file(argv[1]);
    file.write({grid});
    file.close();
    std::printf("wrote %s: %zu active voxels\n", argv[1],
                static_cast<size_t>(grid->activeVoxelCount()));
    return 0;
}
