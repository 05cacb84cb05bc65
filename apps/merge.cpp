// glint merge: checks that frame pieces belong together and cover every pixel's samples once,
// adds them in a fixed order and writes the image (docs/scale-out.md, "Merging").

#include "merge.h"

#include <cstdio>
#include <string>
#include <vector>

#include "cli.h"
#include "glint/io/image/exr_piece.h"
#include "glint/io/image/image_io.h"
#include "options.h"

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
    MergeOptions opt;
    if (int code = parseMergeOptions(argc, argv, opt); code != kGoOn) return code;
    const std::optional<ImageFormat> format = imageFormatFor(opt.output);
    if (!format)
        return mergeUsageError("cannot write '" + opt.output + "': unknown image format (use " +
                               kImageExtensions + ")");

    MergedFrame merged;
    try {
        merged = mergePieceFiles(opt.pieces);
    } catch (const PieceError& e) {
        for (const PieceProblem& p : e.problems()) print(p, "error");
        return kExitSceneError;
    }
    for (const PieceProblem& w : merged.warnings) print(w, "warning");

    // As the pieces were meant to be shown (the scene's display and their command line), unless
    // told otherwise here.
    const DisplayTransform display = opt.shown.over(merged.info.display);
    if (isFloatFormat(*format) && (opt.shown.srgb > 0 || !opt.shown.toneMap.empty()))
        std::fprintf(stderr,
                     "glint merge: warning: --srgb and --tonemap apply to 8-bit outputs (.png, "
                     ".ppm) only; '%s' is written linear\n",
                     opt.output.c_str());
    // The passes the pieces carry go beside the image, as the single render writes them.
    AovSelection aovs = merged.info.aovs;
    if (aovs.any() && *format != ImageFormat::Exr)
        std::fprintf(stderr,
                     "glint merge: warning: the pieces carry render passes (%s), which only an "
                     ".exr output holds; '%s' gets the image alone\n",
                     aovListText(aovs).c_str(), opt.output.c_str());
    if (*format != ImageFormat::Exr) aovs = {};
    try {
        const RenderPasses passes = merged.sums.resolvePasses();
        writeImage(opt.output, merged.sums.resolve(), display, &passes, aovs);
    } catch (const RenderError& e) {
        std::fprintf(stderr, "glint merge: error: %s\n", e.what());
        return kExitSceneError;
    }
    if (!opt.quiet)
        std::fprintf(stderr, "glint merge: wrote %s (%dx%d, %zu piece%s, %d samples per pixel)\n",
                     opt.output.c_str(), merged.info.width, merged.info.height, opt.pieces.size(),
                     opt.pieces.size() == 1 ? "" : "s", merged.info.spp);
    return 0;
}

}  // namespace glint::cli
