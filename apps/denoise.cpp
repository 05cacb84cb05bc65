// glint denoise: reads an OpenEXR render with its passes, denoises it, writes the result
// (docs/denoising.md, "Denoising a saved render").

#include "denoise.h"

#include <cstdio>
#include <string>

#include "cli.h"
#include "glint/core/parallel.h"
#include "glint/denoise/film_denoise.h"
#include "glint/io/image/image_io.h"

namespace glint::cli {

int denoiseMain(int argc, char** argv) {
    CLI::App app{
        "Denoises a render saved as OpenEXR, guided by the render passes the file holds "
        "(albedo,\nnormal, depth, variance: glint --aov all, or glint merge of such pieces). "
        "Without passes it\nestimates the noise from the image alone, which blurs texture.",
        "glint denoise"};
    app.get_formatter()->column_width(30);
    app.failure_message([](const CLI::App*, const CLI::Error& e) {
        return std::string("glint denoise: error: ") + e.what() +
               "\nRun 'glint denoise --help' for usage.\n";
    });
    std::string input, output;
    int threads = 0;
    DisplayOptions shown;
    bool quiet = false;
    app.add_option("INPUT", input, "The render (.exr), with its passes as layers")
        ->required()
        ->type_name("FILE");
    app.add_option("-o,--output", output,
                   "Image file to write; .png, .ppm, .pfm or .exr (an .exr keeps the passes)")
        ->required()
        ->type_name("FILE");
    app.add_option("-t,--threads", threads, "Threads, 1 to 4096 (default: all hardware threads)")
        ->check(integerIn(1, 4096))
        ->type_name("N");
    addDisplayOptions(app, shown, "off");
    app.add_flag("-q,--quiet", quiet, "No messages; errors only");
    app.set_help_flag("-h,--help", "Print this help and exit");
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        int code = app.exit(e);
        return code == 0 ? 0 : kExitUsage;
    }
    const std::optional<ImageFormat> format = imageFormatFor(output);
    if (!format) {
        std::fprintf(stderr,
                     "glint denoise: error: cannot write '%s': unknown image format (use %s)\n"
                     "Run 'glint denoise --help' for usage.\n",
                     output.c_str(), kImageExtensions);
        return kExitUsage;
    }
    try {
        const auto t0 = std::chrono::steady_clock::now();
        const ExrLayers in = readExrLayers(input);
        if (!in.found.albedo && !quiet)
            std::fprintf(stderr,
                         "glint denoise: warning: %s has no albedo pass: texture may be blurred "
                         "(render with --aov all)\n",
                         input.c_str());
        if (!in.found.variance && !quiet)
            std::fprintf(stderr,
                         "glint denoise: warning: %s has no variance pass: the noise is "
                         "estimated from the image\n",
                         input.c_str());
        ThreadPool pool(threads);
        const Film out = denoiseFilm(in.color, in.aovs, pool);
        writeImage(output, out, shown.over({}), &in.aovs,
                   *format == ImageFormat::Exr ? in.found : AovSelection{});
        if (!quiet)
            std::fprintf(stderr, "glint denoise: wrote %s (%dx%d, %.2f s)\n", output.c_str(),
                         out.width(), out.height(), secondsSince(t0));
    } catch (const std::exception& e) {
        std::fprintf(stderr, "glint denoise: error: %s\n", e.what());
        return kExitSceneError;
    }
    return 0;
}

}  // namespace glint::cli
