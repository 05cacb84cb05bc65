// Runs Open Image Denoise's U-Net as Glint infers it (src/glint/denoise/unet/) on float images,
// for checking it against the NumPy reference (tools/unet_reference.py, the test
// denoise.unet_matches_numpy) and for trying weights by hand:
//
//   glint_unet_denoise WEIGHTS.tza COLOR.pfm [ALBEDO.pfm [NORMAL.pfm]] OUT.pfm [--raw]
//   glint_unet_denoise WEIGHTS.tza RENDER.exr OUT.pfm      (its albedo and normal passes)
//
// --list-kernels alone lists the kernels this machine runs. Options: --kernels
// reference|portable|avx2|avx512|simd128 (default: the best), --threads N,
// --time (the network's time), --layers (with --raw: each layer's time and speed too), --tile N
// (tiles of N pixels).
//
// With --raw, the network's own output planes (before the transfer function's inverse) are
// written, and the input is taken as the network's input planes (no exposure, no transfer).
// The time the network took is printed.

#include <chrono>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "glint/core/parallel.h"
#include "glint/denoise/unet/unet_filter.h"
#include "glint/io/image/exr.h"
#include "glint/io/image/image_io.h"
#include "glint/render/film/film.h"

int main(int argc, char** argv) {
    using namespace glint;
    std::vector<std::string> args(argv + 1, argv + argc);
    if (args.size() == 1 && args[0] == "--list-kernels") {
        for (unet::KernelIsa isa :
             {unet::KernelIsa::Reference, unet::KernelIsa::Portable, unet::KernelIsa::Avx2,
              unet::KernelIsa::Avx512, unet::KernelIsa::Simd128})
            if (unet::runs(isa)) std::printf("%s\n", std::string(unet::kernelIsaName(isa)).c_str());
        return 0;
    }
    bool raw = false;
    unet::KernelIsa isa = unet::bestKernelIsa();
    int threads = 0;
    bool layers = false, timed = false;
    int tile = 0;
    for (size_t i = 0; i < args.size();) {
        if (args[i] == "--raw") {
            raw = true;
        } else if (args[i] == "--kernels" && i + 1 < args.size()) {
            isa = unet::kernelIsaNamed(args[i + 1]);
            args.erase(args.begin() + static_cast<long>(i));
        } else if (args[i] == "--layers") {
            layers = true;
        } else if (args[i] == "--tile" && i + 1 < args.size()) {
            tile = std::stoi(args[i + 1]);
            args.erase(args.begin() + static_cast<long>(i));
        } else if (args[i] == "--time") {
            timed = true;
        } else if (args[i] == "--threads" && i + 1 < args.size()) {
            threads = std::stoi(args[i + 1]);
            args.erase(args.begin() + static_cast<long>(i));
        } else {
            ++i;
            continue;
        }
        args.erase(args.begin() + static_cast<long>(i));
    }
    if (args.size() < 3 || args.size() > 5) {
        std::fprintf(stderr,
                     "usage: glint_unet_denoise WEIGHTS.tza COLOR.pfm [ALBEDO.pfm "
                     "[NORMAL.pfm]] OUT.pfm [--raw] [--kernels NAME] [--threads N]\n");
        return 2;
    }
    try {
        const UNet net = UNet::fromTensors(readTza(args[0]));
        std::vector<Film> inputs;
        if (args.size() == 3 && args[1].ends_with(".exr")) {
            ExrLayers exr = readExrLayers(args[1]);
            inputs.push_back(std::move(exr.color));
            for (const std::vector<Vec3>* pass : {&exr.aovs.albedo, &exr.aovs.normal})
                if (!pass->empty())
                    inputs.emplace_back(inputs[0].width(), inputs[0].height(), *pass);
        } else {
            for (size_t i = 1; i + 1 < args.size(); ++i) inputs.push_back(readPfm(args[i]));
        }
        const auto t0 = std::chrono::steady_clock::now();
        const int w = inputs[0].width(), h = inputs[0].height();
        ThreadPool pool(threads);
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
            std::vector<UNetLayerTime> times;
            const FeatureMap y = net.run(x, pool, isa, layers ? &times : nullptr);
            for (const UNetLayerTime& t : times)
                std::fprintf(stderr, "%-12s %5dx%-5d %7.2f ms %6.1f GFLOPS\n", t.name.c_str(),
                             t.width, t.height, 1e3 * t.seconds, 2e-9 * t.multiplyAdds / t.seconds);
            for (int yy = 0; yy < h; ++yy)
                for (int px = 0; px < w; ++px)
                    out.at(px, yy) = Vec3(y.at(0, yy, px), y.at(1, yy, px), y.at(2, yy, px));
        } else {
            UNetImages images{w, h, inputs[0].pixels().data()};
            if (inputs.size() > 1) images.albedo = inputs[1].pixels().data();
            if (inputs.size() > 2) images.normal = inputs[2].pixels().data();
            UNetOptions options;
            options.isa = isa;
            options.tileSize = tile;
            const std::vector<Vec3> result = unetDenoise(net, images, pool, options).pixels;
            for (int y = 0; y < h; ++y)
                for (int x = 0; x < w; ++x) out.at(x, y) = result[static_cast<size_t>(y) * w + x];
        }
        if (timed || layers)
            std::fprintf(
                stderr, "glint_unet_denoise: %dx%d in %.3f s (%s kernels)\n", w, h,
                std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(),
                std::string(unet::kernelIsaName(isa)).c_str());
        writeImage(args.back(), out);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "glint_unet_denoise: %s\n", e.what());
        return 1;
    }
    return 0;
}
