// ThreadPool: every item runs exactly once whatever the thread count, the caller takes part, exceptions reach
// the caller and the pool stays usable afterwards.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <mutex>
#include <set>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "gridtopo/slam/thread_pool.h"

using gridtopo::slam::ThreadPool;

TEST(ThreadPool, ThreadCountIncludesTheCaller) {
  EXPECT_EQ(ThreadPool(1).threads(), 1);
  EXPECT_EQ(ThreadPool(3).threads(), 3);
  const int hw = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  EXPECT_EQ(ThreadPool(0).threads(), hw);
}

TEST(ThreadPool, EveryItemRunsExactlyOnceForAnyThreadCount) {
  for (int threads : {1, 2, 3, 8}) {
    ThreadPool pool(threads);
    for (std::size_t n : {0u, 1u, 2u, 7u, 1000u}) {
      std::vector<std::atomic<int>> runs(n);
      for (auto& r : runs) r = 0;
      pool.parallelFor(n, [&](std::size_t i) { runs[i].fetch_add(1); });
      for (std::size_t i = 0; i < n; ++i) ASSERT_EQ(runs[i].load(), 1) << "threads " << threads << " n " << n << " i " << i;
    }
  }
}

TEST(ThreadPool, ResultsDoNotDependOnTheThreadCount) {
  // Per-item results written to their own slot, then reduced in index order: bit-identical for every pool.
  auto run = [](int threads) {
    ThreadPool pool(threads);
    std::vector<double> out(513);
    pool.parallelFor(out.size(), [&](std::size_t i) {
      double s = 0;
      for (std::size_t k = 1; k <= i + 1; ++k) s += std::sin(static_cast<double>(k * i)) / static_cast<double>(k);
      out[i] = s;
    });
    double total = 0;
    for (double v : out) total += v;
    return std::make_pair(out, total);
  };
  const auto ref = run(1);
  for (int threads : {2, 4, 7}) {
    const auto r = run(threads);
    EXPECT_EQ(r.first, ref.first) << threads;
    EXPECT_EQ(r.second, ref.second) << threads;
  }
}

TEST(ThreadPool, WorkersShareTheItems) {
  // Each item waits (up to 100 ms) until three distinct threads are running items of the loop: with 3 threads the
  // pool must run items on all of them, the caller being one. A worker thread that starts only after a loop began
  // joins it; the check still allows a few loops in case a worker thread takes longer than the items' 100 ms to
  // start on a loaded machine.
  ThreadPool pool(3);
  const auto caller = std::this_thread::get_id();
  std::size_t best = 0;
  bool caller_ran = false;
  for (int attempt = 0; attempt < 50 && best < 3; ++attempt) {
    std::mutex m;
    std::set<std::thread::id> ids;
    std::atomic<bool> by_caller{false};
    pool.parallelFor(3, [&](std::size_t) {
      {
        std::lock_guard<std::mutex> lock(m);
        ids.insert(std::this_thread::get_id());
      }
      if (std::this_thread::get_id() == caller) by_caller = true;
      const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(100);
      for (;;) {
        {
          std::lock_guard<std::mutex> lock(m);
          if (ids.size() == 3) break;
        }
        if (std::chrono::steady_clock::now() > deadline) break;
        std::this_thread::yield();
      }
    });
    if (ids.size() > best) best = ids.size(), caller_ran = by_caller;
  }
  EXPECT_EQ(best, 3u);
  EXPECT_TRUE(caller_ran);
}

TEST(ThreadPool, RethrowsAnItemsExceptionAfterTheOthersFinished) {
  ThreadPool pool(3);
  std::vector<std::atomic<int>> runs(50);
  for (auto& r : runs) r = 0;
  try {
    pool.parallelFor(runs.size(), [&](std::size_t i) {
      runs[i].fetch_add(1);
      if (i == 17) throw std::runtime_error("item 17 failed");
    });
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "item 17 failed");
  }
  // With workers the remaining items still run ("returns when all are done").
  for (std::size_t i = 0; i < runs.size(); ++i) EXPECT_EQ(runs[i].load(), 1) << i;

  // The pool is usable again and the old error is not rethrown.
  std::atomic<int> sum{0};
  EXPECT_NO_THROW(pool.parallelFor(10, [&](std::size_t i) { sum += static_cast<int>(i); }));
  EXPECT_EQ(sum.load(), 45);
}

TEST(ThreadPool, SingleThreadAndSingleItemPropagateExceptions) {
  ThreadPool one(1);
  EXPECT_THROW(one.parallelFor(4, [](std::size_t i) { if (i == 2) throw std::out_of_range("x"); }),
               std::out_of_range);
  ThreadPool many(4);
  EXPECT_THROW(many.parallelFor(1, [](std::size_t) { throw std::logic_error("y"); }), std::logic_error);
}

TEST(ThreadPool, OneOfSeveralExceptionsIsRethrown) {
  ThreadPool pool(4);
  try {
    pool.parallelFor(40, [](std::size_t i) {
      if (i % 10 == 3) throw std::runtime_error("item " + std::to_string(i));
    });
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    const std::string w = e.what();
    EXPECT_TRUE(w == "item 3" || w == "item 13" || w == "item 23" || w == "item 33") << w;
  }
}

TEST(ThreadPool, ManyShortLoopsOnOnePool) {
  // Back-to-back loops (the filter's per-scan use) never lose or repeat an item across generations.
  ThreadPool pool(4);
  long long total = 0;
  for (int loop = 0; loop < 2000; ++loop) {
    const std::size_t n = 1 + static_cast<std::size_t>(loop % 9);
    std::vector<int> hit(n, 0);
    pool.parallelFor(n, [&](std::size_t i) { hit[i] += 1; });
    for (std::size_t i = 0; i < n; ++i) ASSERT_EQ(hit[i], 1) << "loop " << loop << " item " << i;
    total += static_cast<long long>(n);
  }
  EXPECT_EQ(total, 222 * 9 * 5 + (1 + 2));  // 2000 loops = 222 full cycles of 1..9 (45 each) + loops of 1 and 2
}
