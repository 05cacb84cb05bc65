#include "glint/render/renderer.h"

#include <chrono>
#include <condition_variable>
#include <mutex>
#include <thread>
#include <vector>

#include "glint/render/sampler.h"

namespace glint {

RenderResult render(const Scene& scene, const RenderOptions& options) {
    using Clock = std::chrono::steady_clock;
    auto start = Clock::now();
    auto elapsed = [&] { return std::chrono::duration<double>(Clock::now() - start).count(); };

    RenderResult result;
    result.film = Film(scene.width, scene.height);
    const Camera camera(*scene.camera, scene.width, scene.height);
    const WhittedIntegrator integrator(scene);
    const PixelSampler sampler(options.spp, options.seed);
    const double weight = 1.0 / sampler.samplesPerPixel();

    const int tile = std::max(1, options.tileSize);
    const int tilesX = (scene.width + tile - 1) / tile;
    const int tilesY = (scene.height + tile - 1) / tile;
    const int tilesTotal = tilesX * tilesY;
    std::atomic<int> nextTile{0}, tilesDone{0};
    std::mutex mutex;
    std::condition_variable finished;
    int running = 0;

    auto worker = [&] {
        RayCounts counts;
        for (;;) {
            if (options.cancel && options.cancel->load(std::memory_order_relaxed)) break;
            int t = nextTile.fetch_add(1, std::memory_order_relaxed);
            if (t >= tilesTotal) break;
            int x0 = (t % tilesX) * tile, y0 = (t / tilesX) * tile;
            int x1 = std::min(x0 + tile, scene.width), y1 = std::min(y0 + tile, scene.height);
            for (int y = y0; y < y1; ++y)
                for (int x = x0; x < x1; ++x) {
                    Vec3 sum;
                    sampler.forEachSample(x, y, [&](double px, double py) {
                        sum += integrator.li(camera.generateRay(px, py), 0, counts);
                    });
                    result.film.at(x, y) = sampler.samplesPerPixel() == 1 ? sum : sum * weight;
                }
            tilesDone.fetch_add(1, std::memory_order_relaxed);
        }
        std::lock_guard lock(mutex);
        result.rays += counts;
        if (--running == 0) finished.notify_all();
    };

    int threads = options.threads > 0 ? options.threads : hardwareThreads();
    threads = std::min(threads, tilesTotal);
    std::vector<std::thread> pool;
    running = threads;
    for (int i = 0; i < threads; ++i) pool.emplace_back(worker);

    {
        std::unique_lock lock(mutex);
        while (running > 0) {
            finished.wait_for(lock, std::chrono::milliseconds(100), [&] { return running == 0; });
            if (options.onProgress && running > 0) {
                RenderProgress p{tilesDone.load(), tilesTotal, elapsed()};
                lock.unlock();
                options.onProgress(p);
                lock.lock();
            }
        }
    }
    for (auto& t : pool) t.join();

    result.seconds = elapsed();
    result.complete = tilesDone.load() == tilesTotal;
    if (options.onProgress) options.onProgress({tilesDone.load(), tilesTotal, result.seconds});
    return result;
}

}  // namespace glint
