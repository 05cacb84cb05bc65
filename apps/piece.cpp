#include "piece.h"

#include <algorithm>
#include <cstdio>

#include "glint/io/image/image_io.h"
#include "glint/render/adaptive.h"

namespace glint::cli {

bool wantsPiece(const Options& opt) {
    return !opt.crop.empty() || !opt.samples.empty() || !opt.part.empty();
}

namespace {

/// `v` in 17 significant digits: exactly.
std::string exactText(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    return buf;
}

/// The option that made this a piece, for messages.
std::string pieceOption(const Options& opt) {
    if (!opt.part.empty()) return "--part " + opt.part;
    if (!opt.crop.empty()) return "--crop " + opt.crop;
    return "--samples " + opt.samples;
}

}  // namespace

int checkPieceOptions(const Options& opt) {
    const std::string what = pieceOption(opt);
    if (opt.output.empty())
        return usageError(what +
                          " renders a piece of the frame for glint merge: name its OpenEXR file "
                          "with -o FILE.exr");
    if (imageFormatFor(opt.output) != ImageFormat::Exr)
        return usageError(what +
                          " renders a piece of the frame for glint merge, written as "
                          "OpenEXR with its exact sums: '" +
                          opt.output +
                          "' is not an .exr file (merge the pieces into any format with glint "
                          "merge -o OUT)");
    if (opt.timeBudget > 0)
        return usageError(what +
                          ": pieces need a fixed number of samples per pixel (--spp), not --time");
    if (opt.noiseThreshold > 0 && !opt.samples.empty())
        return usageError("--samples " + opt.samples +
                          ": with --noise-threshold each pixel takes its own number of samples; "
                          "split the frame into pieces with --part or --crop");
    if (opt.denoise > 0)
        return usageError(what +
                          ": --denoise: a piece holds its raw sums; denoise the merged image "
                          "(glint merge -o MERGED.exr ...; glint denoise MERGED.exr -o OUT)");
    return kGoOn;
}

int describePiece(const Options& opt, const Prepared& prepared, int spp, uint64_t sceneHash,
                  PieceInfo& out) {
    const Scene& scene = *prepared.scene;
    PieceInfo p;
    p.width = scene.width;
    p.height = scene.height;
    p.crop = {0, p.width, 0, p.height};
    p.tileSize = RenderOptions{}.tileSize;
    p.spp = spp;
    p.sampleEnd = spp;
    const std::string size = std::to_string(p.width) + "x" + std::to_string(p.height);
    if (!opt.crop.empty()) {
        parseCrop(opt.crop, p.crop);  // its form was checked with the options
        if (p.crop.x1 > p.width || p.crop.y1 > p.height)
            return usageError("--crop " + opt.crop + " reaches beyond the " + size +
                              " image: x1 may be at most " + std::to_string(p.width) +
                              " and y1 at most " + std::to_string(p.height));
    }
    if (!opt.samples.empty()) {
        parseSampleRange(opt.samples, p.sampleBegin, p.sampleEnd);
        if (p.sampleEnd > spp)
            return usageError("--samples " + opt.samples + ": the frame has " +
                              std::to_string(spp) + " samples per pixel, so B may be at most " +
                              std::to_string(spp) + " (set them with --spp)");
    }
    if (!opt.part.empty()) {
        parsePart(opt.part, p.part, p.parts);
        // Rows of 16-pixel tiles, or thinner bands when there are more parts than such rows
        // (a small image on a large array): every part then still holds pixels.
        const int height = p.crop.y1 - p.crop.y0;
        if (p.parts > height)
            return usageError("--part " + opt.part + ": the " +
                              (opt.crop.empty() ? "image" : "crop") + " is " +
                              count(static_cast<unsigned long long>(height), "pixel", "pixels") +
                              " high, so N may be at most " + std::to_string(height));
        p.tileSize = std::clamp(height / p.parts, 1, p.tileSize);
        if (p.pixelCount() == 0)  // a crop off the band grid: its last bands fall short
            return usageError("--part " + opt.part + " holds no pixel of the " +
                              (opt.crop.empty() ? "image" : "crop") + "; use fewer parts");
    }
    if (opt.noiseThreshold > 0) {
        p.noiseThreshold = opt.noiseThreshold;
        p.minSpp = std::min(opt.minSpp > 0 ? opt.minSpp : kDefaultMinSpp, spp);
    }
    if (!opt.aov.empty()) parseAovList(opt.aov, p.aovs);  // checked with the options
    p.seed = opt.seed;
    p.sceneHash = sceneHash;
    p.settings = pixelSettings(opt, scene);
    p.version = GLINT_VERSION;
    p.display = prepared.display;
    out = p;
    return kGoOn;
}

void renderPieceWith(const PieceInfo& piece, RenderOptions& ro) {
    ro.crop = piece.crop;
    ro.part = piece.part;
    ro.parts = piece.parts;
    ro.tileSize = piece.tileSize;
    ro.sampleBegin = piece.sampleBegin;
    ro.sampleEnd = piece.sampleEnd;
    ro.keepSums = true;
}

std::string pixelSettings(const Options& opt, const Scene& scene) {
    // The scene's own lines are in the scene hash; these are what the command line changes,
    // with the values in force. Paths are left out (another machine may mount the files
    // elsewhere): a file's contents are in the hash.
    auto orDefault = [](std::string s) {
        if (s.empty()) return std::string("default");
        for (char& c : s)
            if (c == ' ') c = '_';  // settings are words separated by spaces
        return s;
    };
    auto bounceText = [](const BounceLimits& b) {
        auto n = [](int v) {
            return v == BounceLimits::kUnlimited ? std::string("-") : std::to_string(v);
        };
        return n(b.diffuse) + "," + n(b.glossy) + "," + n(b.transmission) + "," + n(b.volume);
    };
    std::string environment = opt.environment;
    if (!environment.empty() && environment != "studio" && environment != "none")
        environment = "file";
    return "integrator=" + orDefault(scene.integrator) +
           " maxdepth=" + std::to_string(scene.maxDepth) +
           (scene.bounces == BounceLimits{} ? std::string()
                                            : " bounces=" + bounceText(scene.bounces)) +
           (scene.clampIndirect > 0 ? " clamp-indirect=" + exactText(scene.clampIndirect)
                                    : std::string()) +
           (scene.caustics ? std::string() : std::string(" caustics=off")) +
           " environment=" + orDefault(environment) + " ground=" + orDefault(opt.ground) +
           " camera=" + orDefault(opt.camera) +
           (opt.fovy > 0 ? " fov=" + exactText(opt.fovy) : std::string()) +
           (opt.seconds()
                ? " animation=" + orDefault(opt.animation) + " time=" + exactText(*opt.seconds())
                : std::string()) +
           " lenient=" + (opt.lenient ? "yes" : "no");
}

}  // namespace glint::cli
