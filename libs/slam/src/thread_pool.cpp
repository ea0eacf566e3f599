#include "gridtopo/slam/thread_pool.h"

#include <algorithm>

namespace gridtopo::slam {

ThreadPool::ThreadPool(int threads) {
  int n = threads > 0 ? threads : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  for (int i = 1; i < n; ++i) workers_.emplace_back([this] { workerLoop(); });
}

ThreadPool::~ThreadPool() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  for (auto& t : workers_) t.join();
}

void ThreadPool::runItems() {
  // Called with mutex_ held; releases it while running items.
  while (next_ < n_) {
    const std::size_t i = next_++;
    const auto* fn = fn_;
    mutex_.unlock();
    std::exception_ptr err;
    try {
      (*fn)(i);
    } catch (...) {
      err = std::current_exception();
    }
    mutex_.lock();
    if (err && !error_) error_ = err;
    ++finished_;
  }
  if (finished_ == n_) done_.notify_all();
}

void ThreadPool::workerLoop() {
  std::unique_lock<std::mutex> lock(mutex_);
  // 0, not generation_: a worker that starts after the first loop began joins it (runItems does nothing once a
  // loop is over).
  std::size_t seen = 0;
  for (;;) {
    wake_.wait(lock, [&] { return stop_ || generation_ != seen; });
    if (stop_) return;
    seen = generation_;
    runItems();
  }
}

void ThreadPool::parallelFor(std::size_t n, const std::function<void(std::size_t)>& fn) {
  if (n == 0) return;
  if (workers_.empty() || n == 1) {
    for (std::size_t i = 0; i < n; ++i) fn(i);
    return;
  }
  std::unique_lock<std::mutex> lock(mutex_);
  fn_ = &fn;
  n_ = n;
  next_ = 0;
  finished_ = 0;
  error_ = nullptr;
  ++generation_;
  wake_.notify_all();
  runItems();
  done_.wait(lock, [&] { return finished_ == n_; });
  fn_ = nullptr;
  n_ = next_ = 0;
  if (error_) std::rethrow_exception(error_);
}

}  // namespace gridtopo::slam
