#include "mpi_tiles.h"

#include <chrono>

namespace glint::mpi {

TileRenderers::TileRenderers(const Scene& scene, const RenderOptions& options,
                             const AdaptiveOptions& adaptive, int threads, Mailbox& mailbox,
                             Take take, Deliver deliver)
    : scene_(scene),
      options_(options),
      adaptive_(adaptive),
      mailbox_(mailbox),
      take_(std::move(take)),
      deliver_(std::move(deliver)),
      pool_(threads + 1),
      group_(pool_) {
    running_ = threads;
    for (int i = 0; i < threads; ++i) group_.run([this] { loop(); });
}

TileRenderers::~TileRenderers() {
    cancel();
    wait();
}

void TileRenderers::cancel() {
    {
        std::lock_guard lock(mailbox_.mutex);
        cancel_.store(true);
    }
    mailbox_.arrived.notify_all();
}

void TileRenderers::wait() {
    try {
        group_.wait();
    } catch (...) {  // loop() keeps its exceptions as error_
    }
}

void TileRenderers::loop() {
    ThreadPool one(1);  // render() runs on this thread alone
    RenderOptions o = options_;
    o.pool = &one;
    o.cancel = &cancel_;
    o.cropFilm = true;
    o.tileSize = 16;  // the renderer's; any size gives the same pixels
    o.onProgress = nullptr;
    try {
        for (;;) {
            std::optional<Tile> tile;
            {
                std::unique_lock lock(mailbox_.mutex);
                if (cancel_.load()) break;
                tile = take_(lock, cancel_);
            }
            if (!tile || cancel_.load()) break;
            o.crop = tile->bounds;
            auto start = std::chrono::steady_clock::now();
            // Each pixel's adaptive stop depends on its own samples: a tile's pixels are the
            // whole frame's.
            RenderResult r =
                adaptive_.threshold > 0 ? renderAdaptive(scene_, o, adaptive_) : render(scene_, o);
            double seconds =
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            if (!r.complete) break;  // cancelled
            deliver_(*tile, std::move(r), seconds);
        }
    } catch (const std::exception& e) {
        std::lock_guard lock(mailbox_.mutex);
        if (error_.empty()) error_ = e.what();
        cancel_.store(true);
    } catch (...) {
        std::lock_guard lock(mailbox_.mutex);
        if (error_.empty()) error_ = "unknown exception";
        cancel_.store(true);
    }
    {
        std::lock_guard lock(mailbox_.mutex);
        --running_;
    }
    mailbox_.arrived.notify_all();
    mailbox_.news.notify_all();
}

std::vector<double> tilePixels(const RenderResult& r, bool passes) {
    const Film& film = r.film;
    std::vector<double> p;
    p.reserve(static_cast<size_t>(film.width()) * film.height() * tileValues(passes));
    for (int y = 0; y < film.height(); ++y)
        for (int x = 0; x < film.width(); ++x) {
            const Vec3& c = film.at(x, y);
            p.insert(p.end(), {c.x, c.y, c.z});
            if (!passes) continue;
            const size_t i = r.aovs.index(x, y);
            for (const Vec3& v :
                 {r.aovs.albedo[i], r.aovs.normal[i], r.aovs.variance[i], r.aovs.albedoVariance[i]})
                p.insert(p.end(), {v.x, v.y, v.z});
            p.push_back(r.aovs.depth[i]);
        }
    return p;
}

void placeTile(const double* p, const PixelBounds& b, Film& film, RenderPasses* aovs) {
    for (int y = b.y0; y < b.y1; ++y)
        for (int x = b.x0; x < b.x1; ++x) {
            film.at(x, y) = Vec3(p[0], p[1], p[2]);
            p += 3;
            if (!aovs) continue;
            const size_t i = aovs->index(x, y);
            aovs->albedo[i] = Vec3(p[0], p[1], p[2]);
            aovs->normal[i] = Vec3(p[3], p[4], p[5]);
            aovs->variance[i] = Vec3(p[6], p[7], p[8]);
            aovs->albedoVariance[i] = Vec3(p[9], p[10], p[11]);
            aovs->depth[i] = p[12];
            p += 13;
        }
}

}  // namespace glint::mpi
