// glint denoise: reads an OpenEXR render with its passes, denoises it, writes the result
// (docs/clean-images.md, "Denoising a saved render").

#include "denoise.h"

#include <cstdio>
#include <string>

#include "cli.h"
#include "glint/core/parallel.h"
#include "glint/denoise/film_denoise.h"
#include "glint/io/image/image_io.h"
#include "options.h"

namespace glint::cli {
namespace {

/// The first `n` bytes of the file at `path` (fewer if it is shorter or cannot be read).
std::string readHead(const std::string& path, size_t n) {
    std::string bytes(n, '\0');
    std::FILE* f = std::fopen(path.c_str(), "rb");
    if (!f) return {};
    bytes.resize(std::fread(bytes.data(), 1, n, f));
    std::fclose(f);
    return bytes;
}

}  // namespace

int denoiseMain(int argc, char** argv) {
    DenoiseOptions opt;
    if (int code = parseDenoiseOptions(argc, argv, opt); code != kGoOn) return code;
    const std::optional<ImageFormat> format = imageFormatFor(opt.output);
    if (!format) {
        std::fprintf(stderr,
                     "glint denoise: error: cannot write '%s': unknown image format (use %s)\n"
                     "Run 'glint denoise --help' for usage.\n",
                     opt.output.c_str(), kImageExtensions);
        return kExitUsage;
    }
    if (std::string problem = denoiserProblem(opt.denoiser, opt.quality); !problem.empty()) {
        std::fprintf(stderr, "glint denoise: error: %s\nRun 'glint denoise --help' for usage.\n",
                     problem.c_str());
        return kExitUsage;
    }
    // OpenEXR alone keeps the float values and the passes the denoiser needs: say so, and how
    // to make one, rather than OpenEXR's "File is not an image file."
    const std::string head = readHead(opt.input, 4);
    if (head.size() == 4 && head != std::string("\x76\x2f\x31\x01", 4)) {
        std::fprintf(stderr,
                     "glint denoise: error: %s is not an OpenEXR file: glint denoise reads renders "
                     "saved as OpenEXR, with their passes (glint SCENE -o render.exr --aov all)\n",
                     opt.input.c_str());
        return kExitSceneError;
    }
    try {
        const auto t0 = std::chrono::steady_clock::now();
        const ExrLayers in = readExrLayers(opt.input);
        if (!in.found.albedo && !opt.quiet)
            std::fprintf(stderr,
                         "glint denoise: warning: %s has no albedo pass: texture may be blurred "
                         "(render with --aov all)\n",
                         opt.input.c_str());
        const FilmDenoiseOptions denoiser = filmDenoiseOptions(opt.denoiser, opt.quality);
        const bool filter = resolveDenoiser(denoiser.denoiser, denoiser.quality, in.found.albedo,
                                            in.found.normal) == DenoiserKind::Nlm;
        if (filter && !in.found.variance && !opt.quiet)
            std::fprintf(stderr,
                         "glint denoise: warning: %s has no variance pass: the noise is "
                         "estimated from the image\n",
                         opt.input.c_str());
        ThreadPool pool(opt.threads);
        FilmDenoiseReport report;
        const Film out = denoiseFilm(in.color, in.aovs, pool, denoiser, &report);
        warnNonFinite("glint denoise", report);
        writeImage(opt.output, out, opt.shown.over({}), &in.aovs,
                   *format == ImageFormat::Exr ? in.found : AovSelection{});
        if (!opt.quiet)
            std::fprintf(stderr, "glint denoise: wrote %s (%dx%d, %s, %.2f s)\n",
                         opt.output.c_str(), out.width(), out.height(), report.method.c_str(),
                         secondsSince(t0));
    } catch (const std::exception& e) {
        std::fprintf(stderr, "glint denoise: error: %s\n", e.what());
        return kExitSceneError;
    }
    return 0;
}

}  // namespace glint::cli
