// A persistent pool of worker threads for the draw's tile work (pipeline.md, "The Device and the
// draw"): the threads are started once per Device, not once per draw, and sleep between draws.
// The caller of run() works too, as worker 0, so a pool of N threads starts N - 1.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace sm2::runtime {

class WorkerPool {
public:
    explicit WorkerPool(unsigned threads);
    ~WorkerPool();
    WorkerPool(const WorkerPool&) = delete;
    WorkerPool& operator=(const WorkerPool&) = delete;

    // Threads run() can use, the caller's included.
    [[nodiscard]] unsigned size() const { return static_cast<unsigned>(threads_.size()) + 1; }
    // Calls job(w) once for every w in [0, workers) (workers <= size()), job(0) on the calling
    // thread, and returns when every call has returned. Not reentrant.
    void run(unsigned workers, const std::function<void(unsigned)>& job);

private:
    void loop(unsigned index);

    std::vector<std::thread> threads_;
    std::mutex mutex_;
    std::condition_variable wake_, done_;
    const std::function<void(unsigned)>* job_ = nullptr;
    unsigned workers_ = 0;                  // workers of the current generation (thread i works if i < workers_)
    std::atomic<unsigned> pending_{0};      // pool threads still running the current job
    std::atomic<uint64_t> generation_{0};
    bool stopping_ = false;
    // Whether a thread waiting for the next job or for the others to finish spins a while
    // before it sleeps: where every thread has a core of its own (a draw every few hundred
    // microseconds, as a scene of many small draws issues them, otherwise paid a sleeping
    // thread's wake-up twice a draw). Not where threads outnumber the cores: there a spinning
    // thread would take the core from one with work.
    bool spin_ = false;
};

}  // namespace sm2::runtime
