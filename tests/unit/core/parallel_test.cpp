#include "glint/core/parallel.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <functional>
#include <mutex>
#include <set>
#include <stdexcept>
#include <thread>
#include <vector>

#include "unit/test_support.h"

namespace glint {
namespace {

using test::processThreads;

TEST(ThreadPool, CountsTheCallerAmongItsThreads) {
    EXPECT_EQ(ThreadPool(1).threads(), 1);
    EXPECT_EQ(ThreadPool(3).threads(), 3);
    EXPECT_EQ(ThreadPool().threads(), hardwareThreads());
    EXPECT_GE(hardwareThreads(), 1);
}

TEST(ThreadPool, StartsOneWorkerFewerThanItsThreads) {
    if (processThreads() < 0) GTEST_SKIP() << "no /proc/self/task";
    const int before = processThreads();
    {
        ThreadPool one(1);
        EXPECT_EQ(processThreads(), before);
    }
    {
        ThreadPool three(3);
        EXPECT_EQ(processThreads(), before + 2);
    }
    EXPECT_EQ(processThreads(), before);
}

TEST(ThreadPool, OneThreadRunsEverythingOnTheCaller) {
    ThreadPool pool(1);
    const std::thread::id caller = std::this_thread::get_id();
    std::vector<std::thread::id> seen;
    std::vector<std::pair<size_t, size_t>> chunks;
    parallelFor(pool, 0, 1000, 10, [&](size_t first, size_t last) {
        seen.push_back(std::this_thread::get_id());
        chunks.emplace_back(first, last);
    });
    // One call over the whole range, on the caller.
    ASSERT_EQ(chunks.size(), 1u);
    EXPECT_EQ(chunks[0], std::make_pair(size_t{0}, size_t{1000}));
    EXPECT_EQ(seen[0], caller);

    // Tasks run at once, inside run().
    TaskGroup group(pool);
    bool ran = false;
    std::thread::id where;
    group.run([&] {
        ran = true;
        where = std::this_thread::get_id();
    });
    EXPECT_TRUE(ran);
    EXPECT_EQ(where, caller);
    group.wait();
}

TEST(ParallelFor, VisitsEveryIndexExactlyOnceInChunksOfTheGrain) {
    for (int threads : {1, 2, 4}) {
        SCOPED_TRACE(testing::Message() << threads << " threads");
        ThreadPool pool(threads);
        const size_t begin = 7, end = 100'007, grain = 13;
        std::vector<std::atomic<int>> visits(end);
        std::atomic<bool> oddChunk{false};
        parallelFor(pool, begin, end, grain, [&](size_t first, size_t last) {
            if (threads > 1 && ((first - begin) % grain != 0 || last - first > grain ||
                                (last - first < grain && last != end)))
                oddChunk = true;
            for (size_t i = first; i < last; ++i) visits[i].fetch_add(1);
        });
        EXPECT_FALSE(oddChunk);
        int wrong = 0;
        for (size_t i = 0; i < end; ++i) wrong += visits[i].load() != (i >= begin ? 1 : 0);
        EXPECT_EQ(wrong, 0);
    }
}

TEST(ParallelFor, AnEmptyRangeCallsNothing) {
    ThreadPool pool(2);
    int calls = 0;
    parallelFor(pool, 5, 5, 1, [&](size_t, size_t) { ++calls; });
    parallelFor(pool, 9, 3, 1, [&](size_t, size_t) { ++calls; });
    EXPECT_EQ(calls, 0);
}

TEST(ParallelFor, SeveralThreadsShareTheWork) {
    // Chunks that wait for each other can only finish if two threads run them at once.
    ThreadPool pool(2);
    std::atomic<int> arrived{0};
    std::set<std::thread::id> ids;
    std::mutex mutex;
    parallelFor(pool, 0, 2, 1, [&](size_t, size_t) {
        {
            std::lock_guard lock(mutex);
            ids.insert(std::this_thread::get_id());
        }
        arrived.fetch_add(1);
        while (arrived.load() < 2) std::this_thread::yield();
    });
    EXPECT_EQ(ids.size(), 2u);
}

TEST(ParallelFor, RethrowsTheFirstExceptionAndStopsHandingOutChunks) {
    for (int threads : {1, 2, 4}) {
        SCOPED_TRACE(testing::Message() << threads << " threads");
        ThreadPool pool(threads);
        std::atomic<int> chunks{0};
        try {
            parallelFor(pool, 0, 10'000, 1, [&](size_t first, size_t) {
                chunks.fetch_add(1);
                if (first == 0) throw std::runtime_error("chunk 0 failed");
                std::this_thread::sleep_for(std::chrono::milliseconds(1));
            });
            ADD_FAILURE() << "no exception";
        } catch (const std::runtime_error& e) {
            EXPECT_STREQ(e.what(), "chunk 0 failed");
        }
        // Chunk 0 is handed out first and fails at once; the others take a millisecond each,
        // so only a few can have started (10 s for all of them).
        EXPECT_LT(chunks.load(), 1000);
        // The pool still works.
        std::atomic<int> sum{0};
        parallelFor(pool, 0, 100, 7, [&](size_t first, size_t last) {
            sum.fetch_add(static_cast<int>(last - first));
        });
        EXPECT_EQ(sum.load(), 100);
    }
}

TEST(TaskGroup, WaitRethrowsATasksExceptionAfterTheOthersRan) {
    for (int threads : {1, 3}) {
        SCOPED_TRACE(testing::Message() << threads << " threads");
        ThreadPool pool(threads);
        TaskGroup group(pool);
        std::atomic<int> ran{0};
        for (int i = 0; i < 20; ++i)
            group.run([&, i] {
                ran.fetch_add(1);
                if (i == 5) throw std::length_error("task 5");
            });
        EXPECT_THROW(group.wait(), std::length_error);
        EXPECT_EQ(ran.load(), 20);
        // The exception was handed over once: the group can be used again.
        group.run([&] { ran.fetch_add(1); });
        EXPECT_NO_THROW(group.wait());
        EXPECT_EQ(ran.load(), 21);
    }
}

/// Sums 1..n by halving, each half a task of a group of its own that the task waits for: waits
/// nest far deeper than there are threads.
long nestedSum(ThreadPool& pool, long lo, long hi) {
    if (hi - lo < 8) {
        long s = 0;
        for (long i = lo; i <= hi; ++i) s += i;
        return s;
    }
    long mid = (lo + hi) / 2, left = 0, right = 0;
    TaskGroup group(pool);
    group.run([&] { left = nestedSum(pool, lo, mid); });
    group.run([&] { right = nestedSum(pool, mid + 1, hi); });
    group.wait();
    return left + right;
}

TEST(TaskGroup, NestedWaitsNeverDeadlock) {
    for (int threads : {1, 2, 4}) {
        SCOPED_TRACE(testing::Message() << threads << " threads");
        ThreadPool pool(threads);
        EXPECT_EQ(nestedSum(pool, 1, 20000), 20000L * 20001 / 2);
        // parallelFor inside parallelFor inside tasks.
        std::atomic<long> sum{0};
        TaskGroup outer(pool);
        for (int t = 0; t < 4; ++t)
            outer.run([&] {
                parallelFor(pool, 0, 50, 3, [&](size_t first, size_t last) {
                    for (size_t i = first; i < last; ++i)
                        parallelFor(pool, 0, 100, 9, [&](size_t f, size_t l) {
                            sum.fetch_add(static_cast<long>(l - f));
                        });
                });
            });
        outer.wait();
        EXPECT_EQ(sum.load(), 4L * 50 * 100);
    }
}

TEST(TaskGroup, TasksMayRunMoreTasksInTheirOwnGroup) {
    for (int threads : {1, 2, 4}) {
        ThreadPool pool(threads);
        TaskGroup group(pool);
        std::atomic<int> ran{0};
        std::function<void(int)> spawn = [&](int depth) {
            ran.fetch_add(1);
            if (depth < 10) {
                group.run([&spawn, depth] { spawn(depth + 1); });
                group.run([&spawn, depth] { spawn(depth + 1); });
            }
        };
        group.run([&] { spawn(0); });
        group.wait();
        EXPECT_EQ(ran.load(), (1 << 11) - 1) << threads << " threads";
    }
}

TEST(TaskGroup, WaitForGivesUpAfterItsTimeout) {
    ThreadPool pool(2);
    TaskGroup group(pool);
    std::atomic<bool> started{false}, release{false};
    group.run([&] {
        started = true;
        while (!release.load()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    });
    // The worker has it (the waiter would otherwise run it, and wait for itself).
    while (!started.load()) std::this_thread::yield();
    auto t0 = std::chrono::steady_clock::now();
    EXPECT_FALSE(group.waitFor(std::chrono::milliseconds(20)));
    EXPECT_GE(std::chrono::steady_clock::now() - t0, std::chrono::milliseconds(20));
    release = true;
    EXPECT_TRUE(group.waitFor(std::chrono::seconds(60)));
}

}  // namespace
}  // namespace glint
