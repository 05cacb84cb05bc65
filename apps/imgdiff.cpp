// imgdiff: compares two images the way the CSE167x grader does and prints hot-pixel counts.
// Exit 0 when the count at --threshold is within --budget, 1 when not, 2 on usage errors.

#include <CLI/CLI.hpp>
#include <cstdio>

#include "glint/core/error.h"
#include "glint/io/image/image_io.h"
#include "glint/io/image/image_diff.h"

int main(int argc, char** argv) {
    CLI::App app{"Counts pixels whose largest channel difference exceeds a threshold.", "imgdiff"};
    std::string a, b, mask;
    int threshold = 2;
    long long budget = 1000;
    app.add_option("A", a, "First image (PNG, JPEG, PPM)")->required();
    app.add_option("B", b, "Second image")->required();
    app.add_option("--mask", mask, "Grey image; pixels where it is non-zero are ignored");
    app.add_option("--threshold", threshold, "Levels of difference a hot pixel exceeds")
        ->check(CLI::Range(0, 255));
    app.add_option("--budget", budget, "Hot pixels allowed (the course allowed 1000)");
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e) == 0 ? 0 : 2;
    }
    try {
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
