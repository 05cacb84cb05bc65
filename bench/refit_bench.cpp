// glint_refit_bench FILE FIRST LAST [STEP] [--fps F] [--size WxH] [--spp N] [--threads N]:
// refitting a sequence's BVHs against building them anew, per frame (docs/performance.md,
// "Animation and motion blur"). FILE is anything `glint FILE --frames FIRST:LAST` renders (an
// animated glTF model, a scene file with `motion`). Each frame is loaded twice: one copy is
// prepared as a sequence prepares it (the last frame's BVHs refitted, Scene::prepare with
// FrameAccel, with no limit on their growth: the refit is always taken, so that what it costs
// over the frames shows), the other built anew. Both are rendered with the same options. Prints
// per frame, and their medians: the prepare times (ms), the summed box areas of the scene's
// tree over its root's (Bvh::relativeArea; search cost grows with it), and the render times.

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "glint/core/error.h"
#include "glint/core/parallel.h"
#include "glint/io/registry.h"
#include "glint/render/renderer.h"

namespace {

double median(std::vector<double> v) {
    if (v.empty()) return 0;
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n % 2 ? v[n / 2] : (v[n / 2 - 1] + v[n / 2]) / 2;
}

double secondsSince(std::chrono::steady_clock::time_point t) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

/// The summed box areas of a scene's tree over its root's.
double area(const glint::Scene& scene) { return scene.bvh().relativeArea(); }

}  // namespace

int main(int argc, char** argv) {
    std::vector<std::string> args(argv + 1, argv + argc);
    double fps = 24;
    int width = 320, height = 180, spp = 4, threads = 2;
    std::vector<std::string> positional;
    for (size_t i = 0; i < args.size(); ++i) {
        const bool more = i + 1 < args.size();
        if (args[i] == "--fps" && more) {
            fps = std::atof(args[++i].c_str());
        } else if (args[i] == "--size" && more) {
            if (std::sscanf(args[++i].c_str(), "%dx%d", &width, &height) != 2) return 2;
        } else if (args[i] == "--spp" && more) {
            spp = std::atoi(args[++i].c_str());
        } else if (args[i] == "--threads" && more) {
            threads = std::atoi(args[++i].c_str());
        } else {
            positional.push_back(args[i]);
        }
    }
    if (positional.size() < 3 || positional.size() > 4 || !(fps > 0) || spp < 1 || threads < 1) {
        std::fprintf(stderr,
                     "usage: glint_refit_bench FILE FIRST LAST [STEP] [--fps F] [--size WxH] "
                     "[--spp N] [--threads N]\n");
        return 2;
    }
    const std::string file = positional[0];
    const int first = std::atoi(positional[1].c_str()), last = std::atoi(positional[2].c_str());
    const int step = positional.size() == 4 ? std::max(1, std::atoi(positional[3].c_str())) : 1;

    glint::AssetCache assets;
    glint::FrameAccel accel;
    glint::ThreadPool pool(threads);
    std::vector<double> refitMs, buildMs, refitArea, builtArea, refitRender, builtRender;
    std::printf("%s, frames %d to %d every %d at %g fps, %dx%d, %d spp, %d threads\n", file.c_str(),
                first, last, step, fps, width, height, spp, threads);
    std::printf("frame  prepare refit/build (ms)  area refit/built  render refit/built (s)\n");
    try {
        for (int frame = first; frame <= last; frame += step) {
            glint::LoadOptions options;
            options.width = width;
            options.height = height;
            options.time.seconds = frame / fps;
            options.assets = &assets;
            std::vector<glint::Diagnostic> warnings;
            auto sequence = glint::loadSceneFile(file, warnings, options).scene;
            auto alone = glint::loadSceneFile(file, warnings, options).scene;
            const bool reuse = accel.kept;
            auto t = std::chrono::steady_clock::now();
            sequence->prepare({.pool = &pool, .reuse = &accel, .refitGrowth = 1e30});
            const double refit = secondsSince(t) * 1e3;
            t = std::chrono::steady_clock::now();
            alone->prepare({.pool = &pool});
            const double build = secondsSince(t) * 1e3;
            glint::RenderOptions o;
            o.threads = threads;
            o.spp = spp;
            o.seed = 1;
            const double renderRefit = glint::render(*sequence, o).seconds;
            const double renderBuilt = glint::render(*alone, o).seconds;
            std::printf("%5d  %7.3f / %7.3f%s  %6.2f / %6.2f  %7.3f / %7.3f\n", frame, refit, build,
                        sequence->bvh().stats().refitted ? "" : " (built)", area(*sequence),
                        area(*alone), renderRefit, renderBuilt);
            if (reuse && sequence->bvh().stats().refitted) {
                refitMs.push_back(refit);
                buildMs.push_back(build);
                refitArea.push_back(area(*sequence));
                builtArea.push_back(area(*alone));
                refitRender.push_back(renderRefit);
                builtRender.push_back(renderBuilt);
            }
            sequence->keepAccel(accel);
        }
    } catch (const glint::SceneError& e) {
        std::fprintf(stderr, "%s\n", e.diagnostic().format("error").c_str());
        return 1;
    }
    std::printf(
        "medians over %zu refitted frames: prepare %.3f ms refit / %.3f ms build (%.2fx); area "
        "%.2f / %.2f (%.2fx); render %.3f / %.3f s (%.3fx)\n",
        refitMs.size(), median(refitMs), median(buildMs),
        median(buildMs) > 0 ? median(refitMs) / median(buildMs) : 0, median(refitArea),
        median(builtArea), median(builtArea) > 0 ? median(refitArea) / median(builtArea) : 0,
        median(refitRender), median(builtRender),
        median(builtRender) > 0 ? median(refitRender) / median(builtRender) : 0);
    return 0;
}
