// SPDX-License-Identifier: MIT
// WorkerPool: workers sleep on a condition variable between runs and claim
// indices from a shared atomic counter during one.
#include "scene/worker_pool.h"

namespace sc::detail {

WorkerPool::~WorkerPool() { stopAll(); }

void WorkerPool::stopAll() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  for (std::thread& t : threads_) t.join();
  threads_.clear();
  stop_ = false;
}

void WorkerPool::resize(int count) {
  if (count < 0) count = 0;
  if (count == workers()) return;
  stopAll();
  threads_.reserve(static_cast<size_t>(count));
  // A worker waits for the generation after the current one; passing it in avoids
  // missing a run that starts before the thread first takes the lock.
  const std::uint64_t current = generation_;
  for (int i = 0; i < count; ++i) threads_.emplace_back([this, current] { workerLoop(current); });
}

void WorkerPool::drain() {
  for (;;) {
    if (failed_.load(std::memory_order_relaxed)) return;
    const int i = next_.fetch_add(1, std::memory_order_relaxed);
    if (i >= count_) return;
    try {
      fn_(context_, i);
    } catch (...) {
      std::lock_guard<std::mutex> lock(mutex_);
      if (!error_) error_ = std::current_exception();
      failed_.store(true, std::memory_order_relaxed);
    }
  }
}

void WorkerPool::workerLoop(std::uint64_t seen) {
  for (;;) {
    {
      std::unique_lock<std::mutex> lock(mutex_);
      wake_.wait(lock, [&] { return stop_ || generation_ != seen; });
      if (stop_) return;
      seen = generation_;
    }
    drain();
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (--busy_ == 0) done_.notify_one();
    }
  }
}

void WorkerPool::runErased(int count, Fn fn, void* context) {
  if (count <= 0) return;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    fn_ = fn;
    context_ = context;
    count_ = count;
    next_.store(0, std::memory_order_relaxed);
    failed_.store(false, std::memory_order_relaxed);
    error_ = nullptr;
    busy_ = workers();
    ++generation_;
  }
  wake_.notify_all();
  drain();
  std::exception_ptr error;
  {
    std::unique_lock<std::mutex> lock(mutex_);
    done_.wait(lock, [&] { return busy_ == 0; });
    error = error_;
    error_ = nullptr;
  }
  if (error) std::rethrow_exception(error);
}

}  // namespace sc::detail
