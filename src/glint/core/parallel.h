#pragma once
/// Threads for everything Glint does in parallel: one pool that the renderer and every phase of
/// the BVH build share, groups of tasks waited for together, and parallelFor over an index range.
///
/// A pool of N threads starts N - 1 workers; the thread that waits for a group is the N-th (it
/// runs queued tasks while it waits). A pool of one thread starts none: every task runs at once
/// on the calling thread. This header and parallel.cpp are the only code that knows about
/// threads (platform code stays behind core/: the library also compiles to WebAssembly).

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstddef>
#include <exception>
#include <functional>
#include <memory>
#include <utility>

namespace glint {

/// The number of threads the machine runs at once (at least 1): what "all threads" means.
int hardwareThreads();

/// Worker threads waiting for tasks. Neither copied nor moved; destroy it only after every task
/// group that uses it has waited.
class ThreadPool {
  public:
    /// A pool of `threads` threads in all, the calling thread included (0: hardwareThreads()):
    /// threads - 1 workers start now.
    explicit ThreadPool(int threads = 0);
    ~ThreadPool();
    ThreadPool(const ThreadPool&) = delete;
    ThreadPool& operator=(const ThreadPool&) = delete;

    /// Threads that run tasks, the caller included (at least 1).
    int threads() const { return threads_; }

  private:
    friend class TaskGroup;
    struct State;  // the queue, its lock and the workers (parallel.cpp)
    int threads_;
    std::unique_ptr<State> state_;
};

/// Tasks waited for together. run() queues a task for any of the pool's threads; wait() returns
/// once every task run in the group has finished, running the group's queued tasks itself
/// meanwhile, newest first. When the group has none queued, the waiter takes another group's
/// newest task, unless it is running such a borrowed task already (so one thread's waits stack
/// at most one borrowed task deep). So a task may run more tasks in its own group or wait for
/// groups of its own: nesting never deadlocks. Idle workers take the oldest task. A task's
/// exception is kept for wait(), which rethrows the first one; the group's other tasks still
/// run.
///
/// With a one-thread pool, run() runs the task at once on the calling thread.
class TaskGroup {
  public:
    explicit TaskGroup(ThreadPool& pool) : pool_(pool) {}
    /// Waits for tasks still queued or running (their exceptions are dropped).
    ~TaskGroup();
    TaskGroup(const TaskGroup&) = delete;
    TaskGroup& operator=(const TaskGroup&) = delete;

    template <typename F>
    void run(F&& task) {
        if (pool_.threads() > 1) return push(std::function<void()>(std::forward<F>(task)));
        try {
            task();
        } catch (...) {
            if (!error_) error_ = std::current_exception();
        }
    }

    /// Returns once every task is done; rethrows the first exception a task threw.
    void wait();
    /// As wait(), but gives up after `timeout` (later if a task it runs meanwhile takes longer):
    /// true if every task is done.
    bool waitFor(std::chrono::milliseconds timeout);

  private:
    void push(std::function<void()> task);
    bool waitUntil(const std::chrono::steady_clock::time_point* deadline);

    friend struct ThreadPool::State;
    ThreadPool& pool_;
    std::atomic<int> pending_{0};  // queued or running; changed under the pool's lock
    std::exception_ptr error_;     // the first thrown; guarded by the pool's lock
};

/// Calls body(first, last) on consecutive chunks [first, last) of [begin, end), `grain` indices
/// each (the last may be shorter), every chunk exactly once, on the pool's threads with the
/// caller among them; chunks go one at a time to whichever thread is free. Returns when all are
/// done. Once a chunk throws no other chunk starts, and the first exception is rethrown. With a
/// one-thread pool, or a range of at most `grain`, body runs once, over the whole range, on the
/// caller.
template <typename Body>
void parallelFor(ThreadPool& pool, size_t begin, size_t end, size_t grain, const Body& body) {
    if (end <= begin) return;
    grain = std::max<size_t>(grain, 1);
    const size_t chunks = (end - begin - 1) / grain + 1;
    if (pool.threads() == 1 || chunks == 1) {
        body(begin, end);
        return;
    }
    std::atomic<size_t> next{0};
    auto work = [&] {
        for (size_t c; (c = next.fetch_add(1, std::memory_order_relaxed)) < chunks;) {
            size_t first = begin + c * grain;
            try {
                body(first, std::min(end, first + grain));
            } catch (...) {
                next.store(chunks, std::memory_order_relaxed);
                throw;
            }
        }
    };
    TaskGroup group(pool);
    const size_t helpers = std::min(static_cast<size_t>(pool.threads()), chunks) - 1;
    for (size_t i = 0; i < helpers; ++i) group.run(work);
    work();  // if it throws, ~TaskGroup waits for the helpers first
    group.wait();
}

}  // namespace glint
