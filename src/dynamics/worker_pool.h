#pragma once
// A small pool of worker threads for the step's independent islands: run(count, task) calls
// task(i) for every i in [0, count), on the workers and on the calling thread, and returns when
// all are done. Which thread takes which index is left to chance, so a task must depend on its
// index alone (each island has its own solvers and scratch; the step merges their reports in
// island order afterwards): the results are then the same bits whatever the thread count.

#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace af {

class WorkerPool {
public:
    // threads − 1 workers: the calling thread is the last one.
    explicit WorkerPool(int threads);
    ~WorkerPool();
    WorkerPool(const WorkerPool&) = delete;
    WorkerPool& operator=(const WorkerPool&) = delete;

    int threads() const { return static_cast<int>(workers_.size()) + 1; }
    // The first exception a task throws is rethrown here, once every task has run or been
    // skipped (after an exception no new index is handed out).
    void run(std::size_t count, const std::function<void(std::size_t)>& task);

private:
    void work(std::stop_token stop);
    void takeTasks(std::unique_lock<std::mutex>& lock);

    std::mutex mutex_;
    std::condition_variable_any wake_;
    std::condition_variable done_;
    const std::function<void(std::size_t)>* task_ = nullptr;
    std::size_t count_ = 0, next_ = 0;
    // Written under the mutex; read without it too, by threads spinning before they sleep.
    std::atomic<std::size_t> finished_ = 0;
    std::atomic<std::size_t> generation_ = 0;
    std::exception_ptr error_;
    std::vector<std::jthread> workers_;
};

}  // namespace af
