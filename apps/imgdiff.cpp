// imgdiff: compares two images.
//   imgdiff A B                  8-bit images the way the CSE167x grader does: hot-pixel counts.
//   imgdiff --blocks N A B       linear float images (EXR, PFM), B the reference: relative
//                                differences of the image means and of N x N block means, RMSE.
//   imgdiff --ssim A B           linear float images as a display shows them: SSIM of the sRGB
//                                luma (Wang et al. 2004), and the relative luminance
//                                differences; --diff D.png pictures the difference.
//   imgdiff --preview OUT.png A  a float image as an sRGB PNG, for looking at.
// Exit 0 when within the limits asked for (--budget, --max-rel), 1 when not, 2 on usage errors
// and unreadable images.

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <string>

#include "glint/core/error.h"
#include "glint/io/image/image_diff.h"
#include "glint/io/image/image_io.h"

namespace {

/// Reads a linear float image: OpenEXR or PFM, by extension.
glint::Film readFloatImage(const std::string& path) {
    std::optional<glint::ImageFormat> f = glint::imageFormatFor(path);
    if (f == glint::ImageFormat::Exr) return glint::readExr(path);
    if (f == glint::ImageFormat::Pfm) return glint::readPfm(path);
    throw glint::RenderError("'" + path + "' is not a float image: --blocks and --preview read " +
                             "OpenEXR (.exr) and PFM (.pfm) files");
}

const char* const kChannel[4] = {"r", "g", "b", "lum"};

void printFour(const char* key, const double v[4]) {
    std::printf("%-10s r=%.6g g=%.6g b=%.6g lum=%.6g\n", key, v[0], v[1], v[2], v[3]);
}

/// The float comparison; returns the exit code.
int compareBlocks(const std::string& a, const std::string& b, int block, double maxRel, bool rgb) {
    glint::Film fa = readFloatImage(a), fb = readFloatImage(b);
    if (fa.width() != fb.width() || fa.height() != fb.height()) {
        std::fprintf(stderr, "imgdiff: error: the images differ in size: %dx%d and %dx%d\n",
                     fa.width(), fa.height(), fb.width(), fb.height());
        return 2;
    }
    glint::FilmComparison r = glint::compareFilms(fa, fb, block);
    std::printf("size       %dx%d, %d blocks of %dx%d pixels; B (%s) is the reference\n", r.width,
                r.height, r.blocks, block, block, b.c_str());
    printFour("mean_a", r.meanA);
    printFour("mean_b", r.meanB);
    printFour("mean_rel", r.meanRel);
    const glint::WorstBlock &wl = r.worstLuminance, &wc = r.worstChannel;
    std::printf("block_rel  lum=%.6g at=%d,%d rgb=%.6g channel=%s rgb_at=%d,%d\n", wl.rel, wl.x,
                wl.y, wc.rel, kChannel[wc.channel], wc.x, wc.y);
    // RMSE relative to the reference's mean luminance (0 for equal images, even black ones).
    double relRmse = r.rmse[3] == 0 ? 0 : r.rmse[3] / r.meanB[3];
    std::printf("rmse       r=%.6g g=%.6g b=%.6g lum=%.6g rel_lum=%.6g\n", r.rmse[0], r.rmse[1],
                r.rmse[2], r.rmse[3], relRmse);
    if (std::isnan(maxRel)) return 0;
    // The checked figures: luminance, or every channel with --rgb. NaN fails.
    double meanWorst = r.meanRel[3], blockWorst = wl.rel;
    if (rgb) {
        meanWorst = std::fmax(std::fmax(r.meanRel[0], r.meanRel[1]), r.meanRel[2]);
        for (int c = 0; c < 3; ++c)
            if (std::isnan(r.meanRel[c])) meanWorst = r.meanRel[c];
        blockWorst = wc.rel;
    }
    bool ok = meanWorst <= maxRel && blockWorst <= maxRel;
    std::printf(
        "%s: %s: relative difference of the image means %.4g, of the block means %.4g; "
        "limit %.4g\n",
        ok ? "PASSED" : "FAILED", rgb ? "largest channel" : "luminance", meanWorst, blockWorst,
        maxRel);
    return ok ? 0 : 1;
}

/// The perceptual comparison; returns the exit code.
int compareSsim(const std::string& a, const std::string& b, double exposure, double minSsim,
                const std::string& diff, double diffScale) {
    glint::Film fa = readFloatImage(a), fb = readFloatImage(b);
    if (fa.width() != fb.width() || fa.height() != fb.height()) {
        std::fprintf(stderr, "imgdiff: error: the images differ in size: %dx%d and %dx%d\n",
                     fa.width(), fa.height(), fb.width(), fb.height());
        return 2;
    }
    if (fa.width() < 11 || fa.height() < 11) {
        std::fprintf(stderr, "imgdiff: error: --ssim needs images of at least 11x11 pixels\n");
        return 2;
    }
    glint::SsimResult s = glint::ssim(glint::displayLuma(fa, exposure),
                                      glint::displayLuma(fb, exposure), fa.width(), fa.height());
    // Luminance: the relative difference of the image means, and the mean absolute
    // difference per pixel relative to the reference's mean.
    double sumA = 0, sumB = 0, sumAbs = 0;
    for (int y = 0; y < fa.height(); ++y)
        for (int x = 0; x < fa.width(); ++x) {
            double la = glint::luminance(fa.at(x, y)), lb = glint::luminance(fb.at(x, y));
            sumA += la;
            sumB += lb;
            sumAbs += std::fabs(la - lb);
        }
    std::printf("size       %dx%d; B (%s) is the reference; display luma at exposure %g\n",
                fa.width(), fa.height(), b.c_str(), exposure);
    std::printf("ssim       mean=%.6g lowest=%.6g at=%d,%d windows=%d\n", s.mean, s.lowest,
                s.lowestX, s.lowestY, s.windows);
    const double pixels = static_cast<double>(fa.width()) * fa.height();
    std::printf("lum        mean_a=%.6g mean_b=%.6g mean_rel=%.6g mae_rel=%.6g\n", sumA / pixels,
                sumB / pixels, glint::relativeDifference(sumA, sumB),
                sumAbs == 0 ? 0.0 : sumAbs / std::fabs(sumB));
    if (!diff.empty()) {
        std::optional<glint::ImageFormat> f = glint::imageFormatFor(diff);
        if (f != glint::ImageFormat::Png && f != glint::ImageFormat::Ppm)
            throw glint::RenderError("--diff writes 8-bit images (.png, .ppm), not '" + diff + "'");
        glint::writeImage(diff, glint::differenceImage(fa, fb, diffScale));
    }
    if (std::isnan(minSsim)) return 0;
    bool ok = s.mean >= minSsim;
    std::printf("%s: mean SSIM %.4g; limit %.4g\n", ok ? "PASSED" : "FAILED", s.mean, minSsim);
    return ok ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{
        "Compares two images. Without --blocks: 8-bit images as the CSE167x grader did, counting "
        "pixels whose largest channel difference exceeds a threshold. With --blocks: linear "
        "float images (EXR, PFM), B the reference. With --ssim: float images as displayed, by "
        "SSIM.",
        "imgdiff"};
    std::string a, b, mask, preview, diff;
    int threshold = 2, block = 0;
    long long budget = 1000;
    double maxRel = NAN, exposure = 0, minSsim = NAN, diffScale = 0.25;
    bool rgb = false, useSsim = false;
    app.add_option("A", a, "First image (PNG, JPEG, PPM; EXR or PFM with --blocks)")->required();
    app.add_option("B", b, "Second image; with --blocks, the reference");
    auto* grader = app.add_option_group("8-bit comparison (the grader's rule)");
    auto* optMask =
        grader->add_option("--mask", mask, "Grey image; pixels where it is non-zero are ignored");
    auto* optThreshold =
        grader->add_option("--threshold", threshold, "Levels of difference a hot pixel exceeds")
            ->check(CLI::Range(0, 255));
    auto* optBudget =
        grader->add_option("--budget", budget, "Hot pixels allowed (the course allowed 1000)");
    auto* floats = app.add_option_group("Float comparison (renders against a reference)");
    auto* optBlocks =
        floats
            ->add_option("--blocks", block,
                         "Compare linear float images in N x N blocks: relative differences "
                         "of the image means and of the block means, and RMSE")
            ->check(CLI::Range(1, 1 << 16));
    auto* optMaxRel =
        floats
            ->add_option("--max-rel", maxRel,
                         "With --blocks: exit 1 when the relative difference of the image "
                         "means or of any block's means exceeds this (luminance)")
            ->check(CLI::NonNegativeNumber);
    auto* optRgb = floats->add_flag("--rgb", rgb,
                                    "With --max-rel: check R, G and B each instead of luminance");
    auto* perceptual = app.add_option_group("Perceptual comparison (SSIM)");
    auto* optSsim = perceptual->add_flag(
        "--ssim", useSsim,
        "Compare linear float images as displayed (sRGB, clamped, --exposure): mean SSIM of "
        "the luma (Wang et al. 2004, 11x11 Gaussian windows), and luminance differences");
    auto* optMinSsim = perceptual
                           ->add_option("--min-ssim", minSsim,
                                        "With --ssim: exit 1 when the mean SSIM is below this")
                           ->check(CLI::Range(-1.0, 1.0));
    auto* optDiff = perceptual->add_option(
        "--diff", diff,
        "With --ssim: write the luminance difference A - B as an 8-bit image (red: A brighter, "
        "blue: darker)");
    auto* optDiffScale =
        perceptual
            ->add_option("--diff-scale", diffScale,
                         "With --diff: the difference shown at full intensity, as a fraction of "
                         "B's mean luminance (default 0.25)")
            ->check(CLI::PositiveNumber);
    auto* out = app.add_option_group("Preview");
    auto* optPreview = out->add_option(
        "--preview", preview,
        "Write the float image A as an 8-bit PNG through the sRGB curve, then exit");
    auto* optExposure =
        out->add_option("--exposure", exposure, "With --preview: multiply by 2^EV first")
            ->check(CLI::Range(-64.0, 64.0));
    optExposure->description("With --preview or --ssim: multiply by 2^EV first");
    try {
        app.parse(argc, argv);
        auto usage = [](const std::string& what) { throw CLI::ValidationError(what); };
        bool graderOpts = optMask->count() || optThreshold->count() || optBudget->count();
        bool ssimOpts =
            optSsim->count() || optMinSsim->count() || optDiff->count() || optDiffScale->count();
        if (optPreview->count()) {
            if (!b.empty() || graderOpts || optBlocks->count() || optMaxRel->count() ||
                optRgb->count() || ssimOpts)
                usage("--preview takes one image and no comparison options");
        } else if (optSsim->count()) {
            if (b.empty()) usage("--ssim compares two images");
            if (graderOpts || optBlocks->count() || optMaxRel->count() || optRgb->count())
                usage("--ssim goes with --min-ssim, --diff, --diff-scale and --exposure only");
            if (optDiffScale->count() && !optDiff->count()) usage("--diff-scale goes with --diff");
        } else {
            if (b.empty()) usage("two images are needed (or --preview OUT.png with one)");
            if (ssimOpts) usage("--min-ssim, --diff and --diff-scale go with --ssim");
            if (optExposure->count()) usage("--exposure goes with --preview or --ssim");
            if (optBlocks->count() && graderOpts)
                usage(
                    "--blocks compares float images: --mask, --threshold and --budget are for "
                    "8-bit ones");
            if (!optBlocks->count() && (optMaxRel->count() || optRgb->count()))
                usage("--max-rel and --rgb go with --blocks");
            if (optRgb->count() && !optMaxRel->count()) usage("--rgb goes with --max-rel");
            if (optMaxRel->count() && !(maxRel >= 0 && std::isfinite(maxRel)))
                usage("--max-rel must be a finite number, at least 0");
        }
    } catch (const CLI::ParseError& e) {
        return app.exit(e) == 0 ? 0 : 2;
    }
    try {
        if (!preview.empty()) {
            glint::Film film = readFloatImage(a);
            std::optional<glint::ImageFormat> f = glint::imageFormatFor(preview);
            if (f != glint::ImageFormat::Png && f != glint::ImageFormat::Ppm)
                throw glint::RenderError("--preview writes 8-bit images (.png, .ppm), not '" +
                                         preview + "'");
            glint::writeImage(preview, film, glint::DisplayTransform{exposure, true});
            return 0;
        }
        if (block > 0) return compareBlocks(a, b, block, maxRel, rgb);
        if (useSsim) return compareSsim(a, b, exposure, minSsim, diff, diffScale);
        glint::Image8 ia = glint::readImage8(a, 3), ib = glint::readImage8(b, 3), im;
        if (!mask.empty()) im = glint::readImage8(mask, 1);
        const glint::Image8* m = mask.empty() ? nullptr : &im;
        for (int t = 0; t <= 2; ++t)
            std::printf("threshold %d: %lld hot pixels\n", t, glint::countHotPixels(ia, ib, t, m));
        std::printf("largest difference: %d\n", glint::maxChannelDifference(ia, ib, m));
        long long hot = glint::countHotPixels(ia, ib, threshold, m);
        std::printf("%s: %lld/%lld allowed hot pixels at threshold %d\n",
                    hot <= budget ? "PASSED" : "FAILED", hot, budget, threshold);
        return hot <= budget ? 0 : 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "imgdiff: error: %s\n", e.what());
        return 2;
    }
}
