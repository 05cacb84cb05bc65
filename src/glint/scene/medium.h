#pragma once
/// Participating media (docs/scene-format.md, "Media"): what fills the space inside a closed
/// surface or the whole scene, absorbing and scattering light as it passes (fog, smoke, milk,
/// wax, jade, skin). pbrt-v4's split: a Medium gives the coefficients at a point and an upper
/// bound of them along a ray (its majorant); the path tracer (render/integrators/media.h) samples
/// points against that bound; a phase function (Henyey-Greenstein) scatters at them.
///
/// Coefficients are per unit of scene length: sigma_a absorbs, sigma_s scatters out, and
/// sigma_t = sigma_a + sigma_s is the extinction; light keeps exp(-sigma_t d) over a distance d
/// (Beer-Lambert). A heterogeneous medium scales both by a density in [0, inf) read from a grid
/// (an OpenVDB file's voxels, scene/ holds only the dense copy, never the library's types).

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "glint/math/transform.h"
#include "glint/math/vec3.h"

namespace glint {

/// A dense grid of densities over a box, trilinearly interpolated between voxel centres, 0
/// outside. Voxel (i, j, k) covers [i, i + 1] x [j, j + 1] x [k, k + 1] of the grid's index
/// space, which `worldFromIndex` places in the scene.
struct DensityGrid {
    int nx = 0, ny = 0, nz = 0;
    std::vector<float> density;  ///< nx * ny * nz values, x fastest; each finite and >= 0.
    Transform worldFromIndex;
    std::string name;  ///< Where it came from (the file and grid), for messages.

    float at(int i, int j, int k) const {
        return density[(static_cast<size_t>(k) * ny + j) * nx + i];
    }
    /// The interpolated density at a point of index space.
    double lookup(const Vec3& pIndex) const;
    /// The largest density in the grid.
    float maxDensity() const;
};

/// Bounds on a density grid's density over coarse blocks of kBlock^3 voxels: the majorants that
/// delta and ratio tracking step through block by block (render/integrators/media.cpp), so that the
/// empty and thin parts of a smoke plume cost few tentative collisions. Block (a, b, c) covers [a
/// kBlock, (a + 1) kBlock] x ... of the grid's index space; its bound is the largest voxel among
/// those DensityGrid::lookup interpolates anywhere inside it (one voxel beyond the block on every
/// side), so it bounds the density there.
struct MajorantGrid {
    static constexpr int kBlock = 8;
    int nx = 0, ny = 0, nz = 0;  ///< Blocks along each axis.
    std::vector<float> bound;    ///< nx * ny * nz bounds, x fastest.

    explicit MajorantGrid(const DensityGrid& grid);
    float at(int a, int b, int c) const {
        return bound[(static_cast<size_t>(c) * ny + b) * nx + a];
    }
};

/// A medium: homogeneous, or scaled by a density grid.
struct Medium {
    std::string name;
    Vec3 sigmaA{0}, sigmaS{0};  ///< Per unit length (at density 1).
    double g = 0;               ///< Henyey-Greenstein asymmetry in (-1, 1): > 0 forwards.
    std::shared_ptr<const DensityGrid> grid;  ///< Null: homogeneous.
    /// Where the grid's index space lies in the scene: the scene's transform (at `medium`)
    /// after the grid's own worldFromIndex. Shared grids keep their own.
    Transform worldFromIndex;
    /// The grid's largest density (1 when homogeneous): with sigma_t, the majorant that
    /// tracking samples against. Set with the grid (grid->maxDensity() visits every voxel).
    double densityBound = 1;
    /// The grid's bounds block by block (null: densityBound everywhere along the grid).
    std::shared_ptr<const MajorantGrid> majorants;

    Vec3 sigmaT() const { return sigmaA + sigmaS; }
    bool homogeneous() const { return grid == nullptr; }
    /// The density at world point p (1 when homogeneous).
    double density(const Vec3& p) const {
        return grid ? grid->lookup(worldFromIndex.inversePoint(p)) : 1.0;
    }
};

}  // namespace glint
