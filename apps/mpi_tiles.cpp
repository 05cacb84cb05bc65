#include "mpi_tiles.h"

#include <chrono>

namespace glint::mpi {

TileRenderers::TileRenderers(const Scene& scene, const RenderOptions& options, int threads,
                             Mailbox& mailbox, Take take, Deliver deliver)
    : scene_(scene),
      options_(options),
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
            RenderResult r = render(scene_, o);
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

}  // namespace glint::mpi
