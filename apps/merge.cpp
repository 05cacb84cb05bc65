// glint merge: checks that frame pieces belong together and cover every pixel's samples once,
// adds them in a fixed order and writes the image (docs/scale-out.md, "Merging").

#include "merge.h"

#include <cstdio>
#include <string>
#include <vector>

#include "cli.h"
#include "glint/io/image/exr_piece.h"
#include "glint/io/image/image_io.h"

namespace glint::cli {

namespace {

void print(const PieceProblem& p, const char* kind) {
    std::fprintf(stderr, "%s: %s: %s\n", p.file.empty() ? "glint merge" : p.file.c_str(), kind,
                 p.message.c_str());
}

int mergeUsageError(const std::string& message) {
    std::fprintf(stderr, "glint merge: error: %s\nRun 'glint merge --help' for usage.\n",
                 message.c_str());
    return kExitUsage;
}

}  // namespace

int mergeMain(int argc, char** argv) {
    CLI::App app{
        "Merges frame pieces that glint rendered with --part, --crop or --samples into one "
        "image,\nexactly the image a single glint run writes (docs/scale-out.md). Checks that "
        "the pieces\nare of one frame (scene, size, samples, seed, settings, version) and cover "
        "each pixel's\nsamples exactly once; they are added in a fixed order whatever the order "
        "named.",
        "glint merge"};
    app.get_formatter()->column_width(30);
    app.failure_message([](const CLI::App*, const CLI::Error& e) {
        return std::string("glint merge: error: ") + e.what() +
               "\nRun 'glint merge --help' for usage.\n";
    });
    std::vector<std::string> pieces;
    std::string output;
    DisplayOptions shown;
    bool quiet = false;
    app.add_option("PIECE", pieces, "Piece files (.exr) that glint wrote")
        ->required()
        ->type_name("FILE");
    app.add_option("-o,--output", output, "Image file to write; .png, .ppm, .pfm or .exr")
        ->required()
        ->type_name("FILE");
    addDisplayOptions(app, shown, "as the pieces were rendered");
    app.add_flag("-q,--quiet", quiet, "No messages; warnings and errors only");
    app.set_help_flag("-h,--help", "Print this help and exit");
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        int code = app.exit(e);
        return code == 0 ? 0 : kExitUsage;
    }
    const std::optional<ImageFormat> format = imageFormatFor(output);
    if (!format)
        return mergeUsageError("cannot write '" + output + "': unknown image format (use " +
                               kImageExtensions + ")");

    MergedFrame merged;
    try {
        merged = mergePieceFiles(pieces);
    } catch (const PieceError& e) {
        for (const PieceProblem& p : e.problems()) print(p, "error");
        return kExitSceneError;
    }
    for (const PieceProblem& w : merged.warnings) print(w, "warning");

    // As the pieces were meant to be shown (the scene's display and their command line), unless
    // told otherwise here.
    const DisplayTransform display = shown.over(merged.info.display);
    if (isFloatFormat(*format) && (shown.srgb > 0 || !shown.toneMap.empty()))
        std::fprintf(stderr,
                     "glint merge: warning: --srgb and --tonemap apply to 8-bit outputs (.png, "
                     ".ppm) only; '%s' is written linear\n",
                     output.c_str());
    // The passes the pieces carry go beside the image, as the single render writes them.
    AovSelection aovs = merged.info.aovs;
    if (aovs.any() && *format != ImageFormat::Exr)
        std::fprintf(stderr,
                     "glint merge: warning: the pieces carry render passes (%s), which only an "
                     ".exr output holds; '%s' gets the image alone\n",
                     aovListText(aovs).c_str(), output.c_str());
    if (*format != ImageFormat::Exr) aovs = {};
    try {
        const RenderPasses passes = merged.sums.resolvePasses();
        writeImage(output, merged.sums.resolve(), display, &passes, aovs);
    } catch (const RenderError& e) {
        std::fprintf(stderr, "glint merge: error: %s\n", e.what());
        return kExitSceneError;
    }
    if (!quiet)
        std::fprintf(stderr, "glint merge: wrote %s (%dx%d, %zu piece%s, %d samples per pixel)\n",
                     output.c_str(), merged.info.width, merged.info.height, pieces.size(),
                     pieces.size() == 1 ? "" : "s", merged.info.spp);
    return 0;
}

}  // namespace glint::cli
