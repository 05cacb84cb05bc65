// Runs Open Image Denoise's U-Net as Glint infers it (src/glint/denoise/unet/) on float images,
// for checking it against the NumPy reference (tools/unet_reference.py, the test
// denoise.unet_matches_numpy) and for trying weights by hand:
//
//   glint_unet_denoise WEIGHTS.tza COLOR.pfm [ALBEDO.pfm [NORMAL.pfm]] OUT.pfm [--raw]
//
// With --raw, the network's own output planes (before the transfer function's inverse) are
// written, and the input is taken as the network's input planes (no exposure, no transfer).

#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "glint/core/parallel.h"
#include "glint/denoise/unet/unet_filter.h"
#include "glint/io/image/image_io.h"
#include "glint/render/film/film.h"

int main(int argc, char** argv) {
    using namespace glint;
    std::vector<std::string> args(argv + 1, argv + argc);
    bool raw = false;
    if (!args.empty() && args.back() == "--raw") {
        raw = true;
        args.pop_back();
    }
    if (args.size() < 3 || args.size() > 5) {
        std::fprintf(stderr,
                     "usage: glint_unet_denoise WEIGHTS.tza COLOR.pfm [ALBEDO.pfm "
                     "[NORMAL.pfm]] OUT.pfm [--raw]\n");
        return 2;
    }
    try {
        const UNet net = UNet::fromTensors(readTza(args[0]));
        std::vector<Film> inputs;
        for (size_t i = 1; i + 1 < args.size(); ++i) inputs.push_back(readPfm(args[i]));
        const int w = inputs[0].width(), h = inputs[0].height();
        ThreadPool pool(0);
        Film out(w, h);
        if (raw) {
            // The input planes as they are, padded with zeros.
            const int aligned = UNet::kAlignment;
            FeatureMap x(net.inputChannels(), (h + aligned - 1) / aligned * aligned,
                         (w + aligned - 1) / aligned * aligned);
            for (size_t k = 0; k < inputs.size(); ++k)
                for (int y = 0; y < h; ++y)
                    for (int px = 0; px < w; ++px)
                        for (int c = 0; c < 3; ++c)
                            x.at(static_cast<int>(3 * k) + c, y, px) =
                                static_cast<float>(inputs[k].at(px, y)[c]);
            const FeatureMap y = net.run(x, pool);
            for (int yy = 0; yy < h; ++yy)
                for (int px = 0; px < w; ++px)
                    out.at(px, yy) = Vec3(y.at(0, yy, px), y.at(1, yy, px), y.at(2, yy, px));
        } else {
            UNetImages images{w, h, inputs[0].pixels().data()};
            if (inputs.size() > 1) images.albedo = inputs[1].pixels().data();
            if (inputs.size() > 2) images.normal = inputs[2].pixels().data();
            const std::vector<Vec3> result = unetDenoise(net, images, pool);
            for (int y = 0; y < h; ++y)
                for (int x = 0; x < w; ++x) out.at(x, y) = result[static_cast<size_t>(y) * w + x];
        }
        writeImage(args.back(), out);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "glint_unet_denoise: %s\n", e.what());
        return 1;
    }
    return 0;
}
