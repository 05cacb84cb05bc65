// glint_aov_split IN.exr PREFIX: writes the beauty image and each render pass an OpenEXR file
// holds (glint --aov) as PFM files, PREFIX.pfm and PREFIX.albedo.pfm, .normal.pfm, .depth.pfm
// (the depth in all three channels), .variance.pfm, and as PNG previews beside them (normals
// mapped from [-1, 1], depth scaled to its largest value): for the denoising benchmark
// (bench/denoise/) and for looking at the passes.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "glint/core/error.h"
#include "glint/io/image/exr.h"
#include "glint/io/image/image_io.h"

namespace {

glint::Film filmOf(int w, int h, const std::vector<glint::Vec3>& v) { return {w, h, v}; }

}  // namespace

int main(int argc, char** argv) {
    if (argc != 3) {
        std::fprintf(stderr, "usage: glint_aov_split IN.exr PREFIX\n");
        return 2;
    }
    try {
        const glint::ExrLayers layers = glint::readExrLayers(argv[1]);
        const std::string prefix = argv[2];
        const int w = layers.color.width(), h = layers.color.height();
        glint::writeImage(prefix + ".pfm", layers.color);
        glint::writeImage(prefix + ".png", layers.color, {0, true, glint::ToneMap::PbrNeutral});
        const glint::RenderPasses& p = layers.aovs;
        auto both = [&](const char* name, const glint::Film& f, const glint::Film& preview) {
            glint::writeImage(prefix + "." + name + ".pfm", f);
            glint::writeImage(prefix + "." + name + ".png", preview);
        };
        if (layers.found.albedo) both("albedo", filmOf(w, h, p.albedo), filmOf(w, h, p.albedo));
        if (layers.found.normal) {
            std::vector<glint::Vec3> shown(p.normal.size());
            for (size_t i = 0; i < shown.size(); ++i)
                shown[i] = (p.normal[i] + glint::Vec3(1)) * 0.5;
            both("normal", filmOf(w, h, p.normal), filmOf(w, h, shown));
        }
        if (layers.found.depth) {
            const double most = *std::max_element(p.depth.begin(), p.depth.end());
            std::vector<glint::Vec3> d(p.depth.size()), shown(p.depth.size());
            for (size_t i = 0; i < d.size(); ++i) {
                d[i] = glint::Vec3(p.depth[i]);
                shown[i] = glint::Vec3(most > 0 ? p.depth[i] / most : 0);
            }
            both("depth", filmOf(w, h, d), filmOf(w, h, shown));
        }
        if (layers.found.variance) {
            std::vector<glint::Vec3> shown(p.variance.size());
            for (size_t i = 0; i < shown.size(); ++i)
                for (int c = 0; c < 3; ++c) shown[i][c] = std::sqrt(p.variance[i][c]) * 4;
            both("variance", filmOf(w, h, p.variance), filmOf(w, h, shown));
        }
        if (!p.albedoVariance.empty()) {
            std::vector<glint::Vec3> shown(p.albedoVariance.size());
            for (size_t i = 0; i < shown.size(); ++i)
                for (int c = 0; c < 3; ++c) shown[i][c] = std::sqrt(p.albedoVariance[i][c]) * 4;
            both("albedoVariance", filmOf(w, h, p.albedoVariance), filmOf(w, h, shown));
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "glint_aov_split: error: %s\n", e.what());
        return 1;
    }
    return 0;
}
