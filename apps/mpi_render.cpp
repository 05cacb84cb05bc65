#include "mpi_render.h"

#include <mpi.h>
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstring>
#include <deque>
#include <optional>
#include <thread>

#include "cli.h"
#include "mpi_protocol.h"
#include "mpi_tiles.h"

namespace glint::mpi {
namespace {

using Clock = std::chrono::steady_clock;

/// How long an MPI thread sleeps between looks for messages when nothing else wakes it: a
/// quarter of the mean tile's render time so far, within 0.5 to 20 ms. A timed sleep costs about
/// 30 us of CPU on a virtual machine (MPI_Iprobe 0.1 us); an answer comes late by up to this,
/// which the tile every rank holds beyond its threads covers.
class PollInterval {
  public:
    void add(double tileSeconds) {
        sum_ += tileSeconds;
        n_ += 1;
    }
    std::chrono::microseconds get() const {
        double us = n_ > 0 ? 1e6 * sum_ / n_ / 4 : 1000;
        return std::chrono::microseconds(static_cast<long>(std::clamp(us, 500.0, 20000.0)));
    }

  private:
    double sum_ = 0;
    double n_ = 0;
};

double threadCpuSeconds() {
    rusage u{};
    ::getrusage(RUSAGE_THREAD, &u);
    return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
           static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec) * 1e-6;
}

/// Receives the next message with `tag` from `source` (any rank: MPI_ANY_SOURCE) if one has
/// arrived; returns its sender, or -1.
int receive(int source, int tag, std::vector<char>& buffer) {
    int flag = 0;
    MPI_Status status;
    MPI_Iprobe(source, tag, MPI_COMM_WORLD, &flag, &status);
    if (!flag) return -1;
    int bytes = 0;
    MPI_Get_count(&status, MPI_BYTE, &bytes);
    buffer.resize(static_cast<size_t>(bytes));
    MPI_Recv(buffer.data(), bytes, MPI_BYTE, status.MPI_SOURCE, tag, MPI_COMM_WORLD,
             MPI_STATUS_IGNORE);
    return status.MPI_SOURCE;
}

/// A worker's messages to rank 0, sent without waiting. MPI_Send of a message above the
/// transport's eager limit (4 KB on shared memory: a 16-pixel tile is 6 KB) returns only once
/// rank 0 has received it, spinning meanwhile; rank 0's MPI thread looks for messages once per
/// poll interval, so in a job of two ranks on two cores that spinning cost rank 1 a third more
/// CPU time than its rendering. MPI_Isend returns at once; the MPI thread looks again later.
class Outbox {
  public:
    Outbox() = default;
    Outbox(const Outbox&) = delete;
    Outbox& operator=(const Outbox&) = delete;
    ~Outbox() { drain(); }

    void send(std::vector<char> message) {
        pending_.push_back({MPI_REQUEST_NULL, std::move(message)});
        Pending& p = pending_.back();
        MPI_Isend(p.message.data(), static_cast<int>(p.message.size()), MPI_BYTE, 0, kTagToRoot,
                  MPI_COMM_WORLD, &p.request);
    }
    /// Forgets the messages rank 0 has taken (in order: MPI delivers them so).
    void progress() {
        while (!pending_.empty()) {
            int done = 0;
            MPI_Test(&pending_.front().request, &done, MPI_STATUS_IGNORE);
            if (!done) return;
            pending_.pop_front();
        }
    }
    /// Waits, sleeping rather than spinning, until rank 0 has taken every message.
    void drain() {
        for (progress(); !pending_.empty(); progress())
            std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }

  private:
    struct Pending {
        MPI_Request request;
        std::vector<char> message;  ///< Its bytes stay put while MPI reads them.
    };
    std::deque<Pending> pending_;
};

/// Rank 0's view of a worker.
struct Worker {
    int outstanding = 0;  ///< Tiles handed to it and not back yet.
    bool stopSent = false, done = false;
};

}  // namespace

int coordinate(const Scene& scene, const RankWork& work, const Job& job,
               const std::atomic<int>& interrupt, Film& film, RenderPasses& aovs,
               FrameFigures& figures, ProgressReporter* progress) {
    const double cpu0 = threadCpuSeconds();
    const auto start = Clock::now();
    auto elapsed = [&] { return std::chrono::duration<double>(Clock::now() - start).count(); };
    const std::vector<PixelBounds> tiles = frameTiles(scene.width, scene.height, work.tileSide);
    const int total = static_cast<int>(tiles.size());
    figures.tiles = total;
    figures.buildSeconds.assign(static_cast<size_t>(job.size), 0);
    figures.buildSeconds[0] = work.buildSeconds;

    // Shared with the render threads, under the mailbox's lock: the next tile to hand out, the
    // tiles in, their times, the rays.
    Mailbox mailbox;
    PollInterval poll;  // under the mailbox's lock
    int next = 0, tilesIn = 0;
    auto takeNext = [&]() -> std::optional<Tile> {
        if (next >= total) return std::nullopt;
        int i = next++;
        return Tile{i, tiles[static_cast<size_t>(i)]};
    };
    const bool passes = work.options.aovs;
    RenderPasses* const frameAovs = passes ? &aovs : nullptr;
    auto deliver = [&](const Tile& t, RenderResult&& r, double seconds) {
        // Disjoint pixels: no lock needed.
        placeTile(tilePixels(r, passes).data(), t.bounds, film, frameAovs);
        {
            std::lock_guard lock(mailbox.mutex);
            ++tilesIn;
            figures.rays += r.rays;
            figures.tileTimes.push_back({t.bounds, 0, seconds});
            poll.add(seconds);
        }
        mailbox.news.notify_all();
    };
    std::optional<TileRenderers> local;
    if (work.buildError.empty())
        local.emplace(
            scene, work.options, work.adaptive, work.threads, mailbox,
            [&](std::unique_lock<std::mutex>&, const std::atomic<bool>&) { return takeNext(); },
            deliver);

    // The first failure, which ends the frame.
    std::string failure;
    auto fail = [&](int rank, const std::string& text) {
        if (failure.empty()) failure = job.name(rank) + " failed: " + text;
    };
    if (!work.buildError.empty()) fail(0, work.buildError);

    std::vector<Worker> workers(static_cast<size_t>(job.size));
    auto send = [&](int rank, const ToWorkerMessage& m) {
        MPI_Send(&m, sizeof m, MPI_BYTE, rank, kTagToWorker, MPI_COMM_WORLD);
        figures.bytesFromRoot += sizeof m;
    };
    auto stopWorker = [&](int rank) {
        Worker& w = workers[static_cast<size_t>(rank)];
        if (w.stopSent) return;
        w.stopSent = true;
        send(rank, {ToWorker::Stop, -1, {}});
    };
    bool stopping = false;
    // Hands worker `rank` up to `count` tiles; stops it once none are left for it.
    auto give = [&](int rank, int count) {
        Worker& w = workers[static_cast<size_t>(rank)];
        bool none = false;
        for (int k = 0; k < count && !stopping; ++k) {
            std::optional<Tile> t;
            {
                std::lock_guard lock(mailbox.mutex);
                t = takeNext();
            }
            if (!t) {
                none = true;
                break;
            }
            send(rank, {ToWorker::Assign, t->index, t->bounds});
            ++w.outstanding;
        }
        if (!none && !stopping) {
            std::lock_guard lock(mailbox.mutex);
            none = next >= total;
        }
        if (stopping || (w.outstanding == 0 && none)) stopWorker(rank);
    };
    auto handle = [&](int rank, const std::vector<char>& m) {
        Worker& w = workers[static_cast<size_t>(rank)];
        ToRootHeader h;
        if (m.size() < sizeof h) return fail(rank, "sent a malformed message");
        std::memcpy(&h, m.data(), sizeof h);
        const char* payload = m.data() + sizeof h;
        const size_t payloadBytes = m.size() - sizeof h;
        switch (h.type) {
            case ToRoot::Request:
                figures.buildSeconds[static_cast<size_t>(rank)] = h.seconds;
                return give(rank, h.count);
            case ToRoot::Result: {
                --w.outstanding;
                if (stopping) return stopWorker(rank);
                if (h.tile < 0 || h.tile >= total) return fail(rank, "sent an unknown tile");
                const PixelBounds& b = tiles[static_cast<size_t>(h.tile)];
                const size_t pixels = static_cast<size_t>(b.x1 - b.x0) * (b.y1 - b.y0);
                if (payloadBytes != pixels * tileValues(passes) * sizeof(double))
                    return fail(rank, "sent a tile of the wrong size");
                placeTile(reinterpret_cast<const double*>(payload), b, film, frameAovs);
                {
                    std::lock_guard lock(mailbox.mutex);
                    ++tilesIn;
                    figures.rays += unpackRays(h.rays);
                    figures.tileTimes.push_back({b, rank, h.seconds});
                    poll.add(h.seconds);
                }
                return give(rank, 1);
            }
            case ToRoot::Error:
                return fail(rank, std::string(payload, payloadBytes));
            case ToRoot::Done:
                w.done = true;
                return;
        }
        fail(rank, "sent a message of unknown type");
    };

    std::vector<char> buffer;
    double lastReport = 0;
    for (;;) {
        if (!stopping) {
            std::string localError;
            if (local) {
                std::lock_guard lock(mailbox.mutex);
                localError = local->error();
            }
            if (!localError.empty()) fail(0, localError);
            if (!failure.empty() || interrupt.load() != 0) {
                stopping = true;
                if (local) local->cancel();
                for (int r = 1; r < job.size; ++r) stopWorker(r);
            }
        }
        for (auto t0 = Clock::now();; t0 = Clock::now()) {
            int r = receive(MPI_ANY_SOURCE, kTagToRoot, buffer);
            if (r < 0) break;
            figures.bytesToRoot += static_cast<double>(buffer.size());
            handle(r, buffer);
            figures.receiveSeconds += std::chrono::duration<double>(Clock::now() - t0).count();
        }
        bool allDone = true;
        for (int r = 1; r < job.size; ++r)
            allDone = allDone && workers[static_cast<size_t>(r)].done;
        std::unique_lock lock(mailbox.mutex);
        if (allDone && (!local || local->finished())) break;
        if (progress && elapsed() - lastReport >= 0.1) {
            lastReport = elapsed();
            progress->update({tilesIn, total, lastReport});
        }
        mailbox.news.wait_for(lock, poll.get());
    }
    if (local) local->wait();
    figures.seconds = elapsed();
    figures.coordinatorCpuSeconds = threadCpuSeconds() - cpu0;
    if (progress && failure.empty() && interrupt.load() == 0)
        progress->finish({tilesIn, total, figures.seconds}, tilesIn == total);
    // A signal to mpirun reaches every rank: then the workers' reports of it are no failure.
    if (interrupt.load() != 0) return kInterrupted;
    if (!failure.empty()) {
        std::fprintf(stderr, "glint-mpi: error: %s; no image written\n", failure.c_str());
        return cli::kExitSceneError;
    }
    if (tilesIn != total) {  // cannot happen: every tile handed out came back or failed
        std::fprintf(stderr, "glint-mpi: error: %d of %d tiles rendered; no image written\n",
                     tilesIn, total);
        return cli::kExitSceneError;
    }
    return cli::kGoOn;
}

int serve(const Scene& scene, const RankWork& work, const Job& job,
          const std::atomic<int>& interrupt) {
    (void)job;
    // Tiles from rank 0 waiting for a render thread, and rendered tiles waiting to be sent.
    Mailbox mailbox;
    std::deque<Tile> waiting;
    bool noMore = false;
    struct Rendered {
        int index;
        std::vector<double> pixels;
        RayCounts rays;
        double seconds;
    };
    std::deque<Rendered> rendered;
    PollInterval poll;  // under the mailbox's lock
    auto take = [&](std::unique_lock<std::mutex>& lock,
                    const std::atomic<bool>& cancelled) -> std::optional<Tile> {
        std::optional<Tile> t;
        mailbox.arrived.wait(lock, [&] { return !waiting.empty() || noMore || cancelled.load(); });
        if (cancelled.load()) return t;
        if (waiting.empty()) return t;
        t = waiting.front();
        waiting.pop_front();
        return t;
    };
    auto deliver = [&](const Tile& t, RenderResult&& r, double seconds) {
        Rendered done{t.index, tilePixels(r, work.options.aovs), r.rays, seconds};
        {
            std::lock_guard lock(mailbox.mutex);
            rendered.push_back(std::move(done));
            poll.add(seconds);
        }
        mailbox.news.notify_all();
    };

    Outbox outbox;
    bool reported = false;  // an Error sent: nothing more but Done
    auto report = [&](const std::string& text) {
        ToRootHeader h;
        h.type = ToRoot::Error;
        outbox.send(packToRoot(h, text.data(), text.size()));
        reported = true;
    };
    std::optional<TileRenderers> local;
    if (work.buildError.empty()) {
        local.emplace(scene, work.options, work.adaptive, work.threads, mailbox, take, deliver);
        ToRootHeader h;
        h.type = ToRoot::Request;
        h.count = work.threads + 1;  // one in hand beyond one per thread: no thread waits
        h.seconds = work.buildSeconds;
        outbox.send(packToRoot(h));
    } else {
        report(work.buildError);
    }

    std::vector<char> buffer;
    bool stopped = false;
    for (;;) {
        std::deque<Rendered> toSend;
        std::string localError;
        {
            std::lock_guard lock(mailbox.mutex);
            toSend.swap(rendered);
            if (local) localError = local->error();
        }
        if (!reported && !localError.empty()) report(localError);
        if (int sig = interrupt.load(); !reported && sig != 0)
            report(std::string("stopped by ") + (sig == SIGTERM ? "SIGTERM" : "SIGINT"));
        if (reported && local) local->cancel();
        for (const Rendered& d : toSend) {
            if (reported || stopped) break;
            ToRootHeader h;
            h.type = ToRoot::Result;
            h.tile = d.index;
            h.seconds = d.seconds;
            packRays(d.rays, h.rays);
            outbox.send(packToRoot(h, d.pixels.data(), d.pixels.size() * sizeof(double)));
        }
        outbox.progress();
        while (receive(0, kTagToWorker, buffer) >= 0) {
            ToWorkerMessage m;
            if (buffer.size() != sizeof m) continue;
            std::memcpy(&m, buffer.data(), sizeof m);
            std::lock_guard lock(mailbox.mutex);
            if (m.type == ToWorker::Assign && !stopped) {
                waiting.push_back({m.tile, m.bounds});
            } else if (m.type == ToWorker::Stop) {
                stopped = true;
                noMore = true;
                waiting.clear();
            }
            mailbox.arrived.notify_all();
        }
        if (stopped && local) local->cancel();
        std::unique_lock lock(mailbox.mutex);
        if (stopped && (!local || local->finished())) break;
        mailbox.news.wait_for(lock, poll.get());
    }
    if (local) local->wait();
    ToRootHeader h;
    h.type = ToRoot::Done;
    outbox.send(packToRoot(h));
    outbox.drain();
    return 0;
}

}  // namespace glint::mpi
