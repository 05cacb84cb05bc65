// unet_speed: the network denoiser's speed (docs/performance.md, "The network denoiser"):
//
//   unet_speed [RUNS] [THREADS]
//
// First this machine's peak of fused multiply-adds: every thread running independent chains of
// 256-bit (AVX2) and 512-bit (AVX-512) FMAs, in GFLOPS (2 per lane per FMA). Then, for 640x480
// and 1920x1080 and each quality (fast, balanced, high), the whole denoise of a colour image
// with albedo and normal as glint calls it (networkDenoise: the transfer function, the tiles,
// the networks, and for high the passes' own networks): the median of RUNS (5) runs after one
// that is not counted, on THREADS threads (2). Then, at 640x480 with the balanced weights, each
// level's layers (UNet::run's times), in GFLOPS counting the network's own channels (not the
// padding of 9 or 3 channels to 16 and 8), and their share of the peak.
//
// The image: smooth colour over several stops with noise, a texture-like albedo and normals
// that turn, so that no layer's output is all zero.

#include <immintrin.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <thread>
#include <vector>

#include "glint/core/parallel.h"
#include "glint/denoise/network_denoise.h"
#include "glint/denoise/unet/blocked.h"
#include "glint/denoise/unet/unet.h"
#include "glint/denoise/unet/unet_filter.h"
#include "glint/math/rng.h"

using namespace glint;

namespace {

using Clock = std::chrono::steady_clock;

double since(Clock::time_point t) {
    return std::chrono::duration<double>(Clock::now() - t).count();
}

#if defined(__x86_64__)
// Twelve independent chains: more than FMA latency times the FMA units, so they never wait.
__attribute__((target("avx2,fma"))) float fma256(long iterations) {
    __m256 a[12];
    for (int i = 0; i < 12; ++i) a[i] = _mm256_set1_ps(0.001f * static_cast<float>(i));
    const __m256 m = _mm256_set1_ps(0.9999f), c = _mm256_set1_ps(0.0001f);
    for (long n = 0; n < iterations; ++n)
#pragma GCC unroll 12
        for (int i = 0; i < 12; ++i) a[i] = _mm256_fmadd_ps(a[i], m, c);
    float s = 0;
    for (int i = 0; i < 12; ++i) s += _mm256_cvtss_f32(a[i]);
    return s;
}

__attribute__((target("avx512f"))) float fma512(long iterations) {
    __m512 a[12];
    for (int i = 0; i < 12; ++i) a[i] = _mm512_set1_ps(0.001f * static_cast<float>(i));
    const __m512 m = _mm512_set1_ps(0.9999f), c = _mm512_set1_ps(0.0001f);
    for (long n = 0; n < iterations; ++n)
#pragma GCC unroll 12
        for (int i = 0; i < 12; ++i) a[i] = _mm512_fmadd_ps(a[i], m, c);
    float s = 0;
    for (int i = 0; i < 12; ++i) s += _mm512_cvtss_f32(a[i]);
    return s;
}

/// GFLOPS of `threads` threads each running `kernel`, the best of three tries.
template <typename Kernel>
double peak(int threads, int lanes, Kernel kernel) {
    const long iterations = 50'000'000 / lanes;
    double best = 0;
    for (int attempt = 0; attempt < 3; ++attempt) {
        std::vector<std::thread> workers;
        std::vector<float> sinks(static_cast<size_t>(threads));
        const auto start = Clock::now();
        for (int t = 0; t < threads; ++t)
            workers.emplace_back([&, t] { sinks[static_cast<size_t>(t)] = kernel(iterations); });
        for (std::thread& w : workers) w.join();
        const double seconds = since(start);
        best = std::max(
            best, 2.0 * 12 * lanes * static_cast<double>(iterations) * threads / seconds / 1e9);
        if (sinks[0] == 12345.f) std::printf(" ");  // keep the sums
    }
    return best;
}
#endif

struct Images {
    int width, height;
    std::vector<Vec3> color, albedo, normal;
};

Images testImages(int width, int height) {
    Images im{width, height, {}, {}, {}};
    Rng rng(7);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const double u = static_cast<double>(x) / width, v = static_cast<double>(y) / height;
            const double light = std::exp2(6 * u - 3) * (0.6 + 0.4 * std::sin(9 * v));
            const Vec3 albedo(0.2 + 0.6 * ((x / 7 + y / 5) % 2), 0.5 + 0.3 * std::sin(x * 0.3),
                              0.4);
            im.albedo.push_back(albedo);
            im.color.push_back(albedo * light * (0.2 + 1.6 * rng.uniform()));
            im.normal.push_back(normalize(Vec3(std::sin(u * 7), std::cos(v * 5), 1)));
        }
    return im;
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
    const int runs = argc > 1 ? std::max(1, std::atoi(argv[1])) : 5;
    const int threads = argc > 2 ? std::max(1, std::atoi(argv[2])) : 2;
    double machinePeak = 0;
#if defined(__x86_64__)
    const double p256 = __builtin_cpu_supports("fma") ? peak(threads, 8, fma256) : 0;
    const double p512 = __builtin_cpu_supports("avx512f") ? peak(threads, 16, fma512) : 0;
    machinePeak = std::max(p256, p512);
    std::printf("FMA peak on %d threads: %.0f GFLOPS with 256-bit vectors, %.0f with 512-bit\n",
                threads, p256, p512);
#endif
    if (!networkDenoiserAvailable(DenoiseQuality::Fast) ||
        !networkDenoiserAvailable(DenoiseQuality::High)) {
        std::printf("no network weights in this build (denoise-weights/README.md)\n");
        return 1;
    }
    std::printf("kernels: %s\n\n", std::string(unet::kernelIsaName(unet::bestKernelIsa())).c_str());
    ThreadPool pool(threads);
    std::printf("| size | fast | balanced | high |\n|---|---|---|---|\n");
    for (const auto& [w, h] : {std::pair{640, 480}, std::pair{1920, 1080}}) {
        const Images im = testImages(w, h);
        DenoiseInput in;
        in.width = w, in.height = h;
        in.color = im.color.data(), in.albedo = im.albedo.data(), in.normal = im.normal.data();
        std::printf("| %dx%d |", w, h);
        for (DenoiseQuality q :
             {DenoiseQuality::Fast, DenoiseQuality::Balanced, DenoiseQuality::High}) {
            std::vector<double> seconds;
            for (int r = 0; r <= runs; ++r) {
                const auto start = Clock::now();
                const NetworkDenoised out = networkDenoise(in, q, pool);
                if (r > 0) seconds.push_back(since(start));
                if (out.color.size() != im.color.size()) return 1;
            }
            std::printf(" %.3f s |", median(seconds));
            std::fflush(stdout);
        }
        std::printf("\n");
    }
    // Each level of the balanced network at 640x480, on its own input planes.
    const auto net = denoiserNetwork("rt_hdr_alb_nrm");
    const Images im = testImages(640, 480);
    const UNetImages images{640, 480, im.color.data(), im.albedo.data(), im.normal.data()};
    const FeatureMap input = unetInput(*net, images, autoexposure(im.color.data(), 640, 480));
    std::vector<std::vector<UNetLayerTime>> all;
    for (int r = 0; r <= runs; ++r) {
        std::vector<UNetLayerTime> times;
        net->run(input, pool, unet::bestKernelIsa(), &times);
        if (r > 0) all.push_back(times);
    }
    std::printf(
        "\n| layers (balanced, 640x480) | size | time | GFLOPS | of the peak |\n"
        "|---|---|---|---|---|\n");
    double total = 0, flops = 0;
    for (size_t i = 0; i < all[0].size(); ++i) {
        std::vector<double> seconds;
        for (const auto& times : all) seconds.push_back(times[i].seconds);
        const double s = median(seconds), f = 2 * all[0][i].multiplyAdds;
        total += s, flops += f;
        std::printf("| %s | %dx%d | %.1f ms | %.0f | %.0f%% |\n", all[0][i].name.c_str(),
                    all[0][i].width, all[0][i].height, 1e3 * s, f / s / 1e9,
                    machinePeak > 0 ? 100 * f / s / 1e9 / machinePeak : 0.0);
    }
    std::printf("| all | 640x480 | %.1f ms | %.0f | %.0f%% |\n", 1e3 * total, flops / total / 1e9,
                machinePeak > 0 ? 100 * flops / total / 1e9 / machinePeak : 0.0);
    return 0;
}
