#include "worker_pool.h"

#include <chrono>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

namespace sm2::runtime {

namespace {

// How long a waiting thread spins before it sleeps: a little more than a small draw's set-up
// between two draws' tile work, far below a frame.
constexpr auto kSpin = std::chrono::microseconds(100);

void relax() {
#if defined(__x86_64__) || defined(__i386__)
    _mm_pause();
#endif
}

// Spins until `ready()` or kSpin has passed; returns ready()'s last answer.
template <class Ready>
bool spin_until(Ready ready) {
    const auto until = std::chrono::steady_clock::now() + kSpin;
    for (unsigned i = 0;; ++i) {
        if (ready()) return true;
        if (i % 64 == 63 && std::chrono::steady_clock::now() > until) return false;
        relax();
    }
}

}  // namespace

WorkerPool::WorkerPool(unsigned threads) {
    const unsigned extra = threads > 1 ? threads - 1 : 0;
    const unsigned cores = std::thread::hardware_concurrency();
    spin_ = extra > 0 && cores != 0 && threads <= cores;
    threads_.reserve(extra);
    for (unsigned i = 0; i < extra; ++i) threads_.emplace_back([this, i] { loop(i + 1); });
}

WorkerPool::~WorkerPool() {
    {
        std::lock_guard lock(mutex_);
        stopping_ = true;
        generation_.fetch_add(1, std::memory_order_release);  // ends a spin
    }
    wake_.notify_all();
    for (auto& t : threads_) t.join();
}

void WorkerPool::run(unsigned workers, const std::function<void(unsigned)>& job) {
    workers = workers < 1 ? 1 : workers > size() ? size() : workers;
    if (workers > 1) {
        {
            std::lock_guard lock(mutex_);
            job_ = &job;
            workers_ = workers;
            pending_.store(workers - 1, std::memory_order_relaxed);
            generation_.fetch_add(1, std::memory_order_release);
        }
        wake_.notify_all();
    }
    job(0);
    if (workers > 1) {
        const auto finished = [this] { return pending_.load(std::memory_order_acquire) == 0; };
        if (!(spin_ && spin_until(finished))) {
            std::unique_lock lock(mutex_);
            done_.wait(lock, finished);
        }
        std::lock_guard lock(mutex_);
        job_ = nullptr;
    }
}

void WorkerPool::loop(unsigned index) {
    uint64_t seen = 0;
    for (;;) {
        const auto next = [&] { return generation_.load(std::memory_order_acquire) != seen; };
        if (spin_) spin_until(next);
        const std::function<void(unsigned)>* job = nullptr;
        {
            std::unique_lock lock(mutex_);
            wake_.wait(lock, [&] { return stopping_ || next(); });
            if (stopping_) return;
            seen = generation_.load(std::memory_order_relaxed);
            if (index >= workers_) continue;  // this generation needs fewer threads
            job = job_;
        }
        (*job)(index);
        if (pending_.fetch_sub(1, std::memory_order_acq_rel) == 1) {
            // (Under the lock: run() tests `pending_` under it before it sleeps, so the notice
            // cannot fall between its test and its wait.)
            std::lock_guard lock(mutex_);
            done_.notify_one();
        }
    }
}

}  // namespace sm2::runtime
