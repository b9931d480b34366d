// The draw's persistent worker pool: every run() calls the job once per requested worker, the
// caller being worker 0, and returns only after all of them have returned.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <thread>
#include <vector>

#include "worker_pool.h"

namespace sm2::runtime {
namespace {

TEST(WorkerPool, EveryWorkerRunsOncePerRunAndTheCallerIsWorkerZero) {
    WorkerPool pool(3);
    ASSERT_EQ(pool.size(), 3u);
    const auto caller = std::this_thread::get_id();
    for (unsigned round = 0; round < 200; ++round) {
        const unsigned workers = 1 + round % 3;
        std::vector<std::atomic<int>> calls(3);
        std::atomic<bool> zero_on_caller{false};
        pool.run(workers, [&](unsigned w) {
            calls[w].fetch_add(1);
            if (w == 0) zero_on_caller = std::this_thread::get_id() == caller;
        });
        // run() has returned: every call is complete and visible.
        for (unsigned w = 0; w < 3; ++w) EXPECT_EQ(calls[w].load(), w < workers ? 1 : 0) << "round " << round;
        EXPECT_TRUE(zero_on_caller.load());
    }
}

TEST(WorkerPool, MoreWorkersThanThreadsAreClampedAndOneThreadRunsInline) {
    WorkerPool single(1);
    EXPECT_EQ(single.size(), 1u);
    int calls = 0;
    single.run(4, [&](unsigned w) {
        EXPECT_EQ(w, 0u);
        ++calls;
    });
    EXPECT_EQ(calls, 1);

    WorkerPool pair(2);
    std::atomic<int> total{0};
    pair.run(8, [&](unsigned) { total.fetch_add(1); });
    EXPECT_EQ(total.load(), 2);
}

TEST(WorkerPool, WorkIsSharedThroughACounter) {
    WorkerPool pool(2);
    std::atomic<size_t> next{0};
    std::vector<int> done(10000, 0);
    pool.run(2, [&](unsigned) {
        for (size_t k = next.fetch_add(1); k < done.size(); k = next.fetch_add(1)) done[k] += 1;
    });
    for (int d : done) ASSERT_EQ(d, 1);
}

// Runs back to back (a waiting thread still spinning where the pool has a core per thread) and
// runs after a pause longer than any spin (the worker asleep): each calls every worker once, and
// run() returns only after all of them.
TEST(WorkerPool, BackToBackAndSpacedRunsCallEveryWorkerOnce) {
    WorkerPool pool(2);
    for (unsigned round = 0; round < 400; ++round) {
        if (round % 40 == 0) std::this_thread::sleep_for(std::chrono::milliseconds(2));
        const unsigned workers = 1 + round % 2;
        std::vector<std::atomic<int>> calls(2);
        pool.run(workers, [&](unsigned w) {
            if (w == 1 && round % 3 == 0) std::this_thread::sleep_for(std::chrono::microseconds(300));  // the caller waits
            calls[w].fetch_add(1);
        });
        for (unsigned w = 0; w < 2; ++w) ASSERT_EQ(calls[w].load(), w < workers ? 1 : 0) << "round " << round;
    }
}

}  // namespace
}  // namespace sm2::runtime
