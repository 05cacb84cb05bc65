#pragma once
/// What a light pass (render/integrators/caustics.h) gives a render: light splatted into the image,
/// and photons for the camera's paths to gather.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "glint/math/vec3.h"

namespace glint {

/// Photons left on surfaces, gathered by a density estimate within a fixed radius (Jensen's
/// caustic photon map, searched through a hashed grid of cells as wide as the search).
class PhotonMap {
  public:
    struct Photon {
        Vec3f p;           ///< Where it landed.
        Vec3f power;       ///< Its throughput: flux in the units of a path's (caustics.cpp).
        Vec3f wi;          ///< Unit direction it came from.
        Vec3f ng;          ///< The surface's unit geometric normal there.
        uint32_t casters;  ///< The casters it passed from the light.
    };

    PhotonMap() = default;
    /// Photons of `paths` light paths, gathered within `radius`.
    PhotonMap(std::vector<Photon> photons, double radius, double paths);

    bool empty() const { return photons_.empty(); }
    size_t size() const { return photons_.size(); }
    double radius() const { return radius_; }

    /// The sum of weight(photon) times its power over the photons within the radius of `p` that
    /// landed on a surface facing as `ng` does after at most `maxCasters` casters, over pi r^2
    /// and the number of light paths: the density estimate of light leaving `p` when weight
    /// gives the BSDF's share.
    template <typename Weight>
    Vec3 gather(const Vec3& p, const Vec3& ng, uint32_t maxCasters, const Weight& weight) const {
        Vec3 sum(0);
        if (photons_.empty()) return sum;
        const double r2 = radius_ * radius_;
        // The cells of side 2r holding the ball's box: two along each axis.
        const double inv = 1 / (2 * radius_);
        const int64_t x0 = cell((p.x - radius_) * inv), y0 = cell((p.y - radius_) * inv),
                      z0 = cell((p.z - radius_) * inv);
        for (int64_t dz = 0; dz < 2; ++dz)
            for (int64_t dy = 0; dy < 2; ++dy)
                for (int64_t dx = 0; dx < 2; ++dx) {
                    const uint32_t b = bucket(x0 + dx, y0 + dy, z0 + dz);
                    for (uint32_t i = start_[b]; i < start_[b + 1]; ++i) {
                        const Photon& ph = photons_[i];
                        const Vec3 d = Vec3(ph.p) - p;
                        if (dot(d, d) > r2 || dot(Vec3(ph.ng), ng) < 0.5 || ph.casters > maxCasters)
                            continue;
                        sum += weight(Vec3(ph.wi)) * Vec3(ph.power);
                    }
                }
        return sum * scale_;
    }

    /// The cell of coordinate `v` (in cells), clamped far beyond any scene's so that the
    /// conversion is defined.
    static int64_t cell(double v) {
        return static_cast<int64_t>(std::floor(std::clamp(v, -1e15, 1e15)));
    }

  private:
    uint32_t bucket(int64_t x, int64_t y, int64_t z) const {
        uint64_t h = static_cast<uint64_t>(x) * 73856093ULL ^
                     static_cast<uint64_t>(y) * 19349663ULL ^
                     static_cast<uint64_t>(z) * 83492791ULL;
        return static_cast<uint32_t>(h & mask_);
    }

    std::vector<Photon> photons_;  ///< Sorted by bucket.
    std::vector<uint32_t> start_;  ///< Bucket b's photons are [start_[b], start_[b + 1]).
    uint64_t mask_ = 0;
    double radius_ = 0, scale_ = 0;
};

/// A light pass's result for camera sample indices [begin, end) of a render.
struct LightPassResult {
    /// Per pixel of the scene's image (row by row): the sum over those indices of the light
    /// splatted there, added to the sum of the pixel's samples.
    std::vector<Vec3> image;
    /// For the camera's paths to gather where they see a surface through casters.
    PhotonMap photons;
};

}  // namespace glint
