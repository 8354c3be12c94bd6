// The step's worker threads; see worker_pool.h.

#include "worker_pool.h"

namespace af {

WorkerPool::WorkerPool(int threads) {
    for (int i = 1; i < threads; ++i) workers_.emplace_back([this](std::stop_token stop) { work(stop); });
}

WorkerPool::~WorkerPool() {
    for (std::jthread& worker : workers_) worker.request_stop();
    wake_.notify_all();
}

void WorkerPool::run(std::size_t count, const std::function<void(std::size_t)>& task) {
    std::unique_lock lock(mutex_);
    task_ = &task;
    count_ = count;
    next_ = finished_ = 0;
    error_ = nullptr;
    ++generation_;
    wake_.notify_all();
    takeTasks(lock);
    done_.wait(lock, [this] { return finished_ == count_; });
    task_ = nullptr;
    if (error_) std::rethrow_exception(error_);
}

// Takes indices until none is left; the lock is held between tasks, not during them.
void WorkerPool::takeTasks(std::unique_lock<std::mutex>& lock) {
    while (task_ && next_ < count_) {
        const std::size_t index = next_++;
        const std::function<void(std::size_t)>& task = *task_;
        lock.unlock();
        std::exception_ptr error;
        try {
            task(index);
        } catch (...) {
            error = std::current_exception();
        }
        lock.lock();
        if (error && !error_) {
            error_ = error;
            finished_ += count_ - next_;  // what no one will take now
            next_ = count_;
        }
        if (++finished_ == count_) done_.notify_all();
    }
}

void WorkerPool::work(std::stop_token stop) {
    std::unique_lock lock(mutex_);
    std::size_t seen = generation_;
    while (true) {
        wake_.wait(lock, stop, [&] { return generation_ != seen; });
        if (stop.stop_requested()) return;
        seen = generation_;
        takeTasks(lock);
    }
}

}  // namespace af
