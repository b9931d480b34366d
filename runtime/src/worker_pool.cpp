#include "worker_pool.h"

namespace sm2::runtime {

WorkerPool::WorkerPool(unsigned threads) {
    const unsigned extra = threads > 1 ? threads - 1 : 0;
    threads_.reserve(extra);
    for (unsigned i = 0; i < extra; ++i) threads_.emplace_back([this, i] { loop(i + 1); });
}

WorkerPool::~WorkerPool() {
    {
        std::lock_guard lock(mutex_);
        stopping_ = true;
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
            pending_ = workers - 1;
            ++generation_;
        }
        wake_.notify_all();
    }
    job(0);
    if (workers > 1) {
        std::unique_lock lock(mutex_);
        done_.wait(lock, [this] { return pending_ == 0; });
        job_ = nullptr;
    }
}

void WorkerPool::loop(unsigned index) {
    uint64_t seen = 0;
    for (;;) {
        const std::function<void(unsigned)>* job = nullptr;
        {
            std::unique_lock lock(mutex_);
            wake_.wait(lock, [&] { return stopping_ || generation_ != seen; });
            if (stopping_) return;
            seen = generation_;
            if (index >= workers_) continue;  // this generation needs fewer threads
            job = job_;
        }
        (*job)(index);
        {
            std::lock_guard lock(mutex_);
            if (--pending_ == 0) done_.notify_one();
        }
    }
}

}  // namespace sm2::runtime
