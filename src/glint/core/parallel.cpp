#include "glint/core/parallel.h"

#include <condition_variable>
#include <deque>
#include <mutex>
#include <thread>
#include <vector>

namespace glint {

int hardwareThreads() {
    unsigned n = std::thread::hardware_concurrency();
    return n ? static_cast<int>(n) : 1;
}

namespace {

/// Whether this thread is running a task it took from another group while waiting for its own.
/// It then takes only its own groups' tasks, so that waits do not pile up on one stack.
thread_local bool tBorrowed = false;

}  // namespace

struct ThreadPool::State {
    struct Task {
        std::function<void()> fn;
        TaskGroup* group;
    };

    std::mutex mutex;
    std::condition_variable workersWake;  // a task was queued, or the pool stops
    std::condition_variable waitersWake;  // a task was queued, or a group finished
    std::deque<Task> queue;               // oldest first
    int idleWorkers = 0, sleepingWaiters = 0;
    bool stopping = false;
    std::vector<std::thread> workers;

    /// Runs `task` with the lock released (held again on return) and records that it is done.
    void run(Task& task, std::unique_lock<std::mutex>& lock) {
        lock.unlock();
        std::exception_ptr error;
        try {
            task.fn();
        } catch (...) {
            error = std::current_exception();
        }
        task.fn = nullptr;  // its captures go before the group can be seen done
        lock.lock();
        TaskGroup& group = *task.group;
        if (error && !group.error_) group.error_ = error;
        if (--group.pending_ == 0 && sleepingWaiters > 0) waitersWake.notify_all();
    }

    /// A worker: the oldest queued task first (the largest, when tasks split work).
    void work() {
        std::unique_lock lock(mutex);
        for (;;) {
            if (!queue.empty()) {
                Task task = std::move(queue.front());
                queue.pop_front();
                run(task, lock);
            } else if (stopping) {
                return;
            } else {
                ++idleWorkers;
                workersWake.wait(lock);
                --idleWorkers;
            }
        }
    }

    void stop() {
        {
            std::lock_guard lock(mutex);
            stopping = true;
        }
        workersWake.notify_all();
        for (std::thread& w : workers) w.join();
    }
};

ThreadPool::ThreadPool(int threads) : threads_(threads > 0 ? threads : hardwareThreads()) {
    if (threads_ == 1) return;
    state_ = std::make_unique<State>();
    try {
        state_->workers.reserve(static_cast<size_t>(threads_ - 1));
        for (int i = 1; i < threads_; ++i)
            state_->workers.emplace_back([s = state_.get()] { s->work(); });
    } catch (...) {
        state_->stop();
        throw;
    }
}

ThreadPool::~ThreadPool() {
    if (state_) state_->stop();
}

TaskGroup::~TaskGroup() {
    try {
        wait();
    } catch (...) {
    }
}

void TaskGroup::push(std::function<void()> task) {
    ThreadPool::State& s = *pool_.state_;
    std::lock_guard lock(s.mutex);
    s.queue.push_back({std::move(task), this});
    ++pending_;
    if (s.idleWorkers > 0) s.workersWake.notify_one();
    if (s.sleepingWaiters > 0) s.waitersWake.notify_all();
}

void TaskGroup::wait() { waitUntil(nullptr); }

bool TaskGroup::waitFor(std::chrono::milliseconds timeout) {
    auto deadline = std::chrono::steady_clock::now() + timeout;
    return waitUntil(&deadline);
}

bool TaskGroup::waitUntil(const std::chrono::steady_clock::time_point* deadline) {
    std::exception_ptr error;
    // Without the lock when nothing is queued or running (the last task's decrement, made
    // under the lock after it recorded its exception, is what this load sees).
    if (pool_.threads() == 1 || pending_.load(std::memory_order_acquire) == 0) {
        error = std::exchange(error_, nullptr);
    } else {
        ThreadPool::State& s = *pool_.state_;
        std::unique_lock lock(s.mutex);
        while (pending_ > 0) {
            if (deadline && std::chrono::steady_clock::now() >= *deadline) return false;
            // The group's newest queued task, else (unless borrowing already) any newest one.
            auto it = s.queue.end();
            for (auto i = s.queue.end(); i != s.queue.begin();)
                if ((--i)->group == this) {
                    it = i;
                    break;
                }
            if (it == s.queue.end() && !tBorrowed && !s.queue.empty()) it = std::prev(it);
            if (it != s.queue.end()) {
                ThreadPool::State::Task task = std::move(*it);
                s.queue.erase(it);
                const bool borrowed = tBorrowed;
                tBorrowed = borrowed || task.group != this;
                s.run(task, lock);
                tBorrowed = borrowed;
                continue;
            }
            ++s.sleepingWaiters;
            if (deadline)
                s.waitersWake.wait_until(lock, *deadline);
            else
                s.waitersWake.wait(lock);
            --s.sleepingWaiters;
        }
        error = std::exchange(error_, nullptr);
    }
    if (error) std::rethrow_exception(error);
    return true;
}

}  // namespace glint
