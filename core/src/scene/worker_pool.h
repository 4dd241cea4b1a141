// SPDX-License-Identifier: MIT
// A small pool of std::threads owned by a scene: runs task(i) for i in [0, n) on
// the calling thread and the workers, and returns when every index is done.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace sc::detail {

class WorkerPool {
 public:
  WorkerPool() = default;
  ~WorkerPool();
  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;

  /// Keeps `count` worker threads besides the caller (joins or starts them).
  void resize(int count);
  int workers() const { return static_cast<int>(threads_.size()); }

  /// Calls task(i) once for every i in [0, count), spread over the caller and the
  /// workers in no particular order. Rethrows the first exception a task threw
  /// (the remaining indices are skipped then). Not reentrant.
  template <class Task>
  void run(int count, Task& task) {
    runErased(count, &invoke<Task>, &task);
  }

 private:
  using Fn = void (*)(void*, int);
  template <class Task>
  static void invoke(void* task, int i) {
    (*static_cast<Task*>(task))(i);
  }
  void runErased(int count, Fn fn, void* context);
  void workerLoop(std::uint64_t seen);
  void drain();
  void stopAll();

  std::vector<std::thread> threads_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::condition_variable done_;
  std::uint64_t generation_ = 0;  ///< bumped per run; workers wait for a change
  int busy_ = 0;                  ///< workers still inside the current run
  bool stop_ = false;
  Fn fn_ = nullptr;
  void* context_ = nullptr;
  int count_ = 0;
  std::atomic<int> next_{0};
  std::atomic<bool> failed_{false};
  std::exception_ptr error_;
};

}  // namespace sc::detail
