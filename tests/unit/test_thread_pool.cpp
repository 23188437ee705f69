// threads::parallel_for: every index once on any thread count, the lowest failing index's
// exception, nested loops serial, and workers that take no CPU while they wait.
#include <gtest/gtest.h>
#include <sys/resource.h>

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "core/thread_pool.h"

namespace impactfe::test_thread_pool {
namespace {

struct ThreadLimit {
  explicit ThreadLimit(int n) : saved(threads::max_threads()) { threads::set_max_threads(n); }
  ~ThreadLimit() { threads::set_max_threads(saved); }
  int saved;
};

TEST(ThreadPool, EveryIndexOnceWhateverTheThreads) {
  for (int t : {1, 2, 3, 8}) {
    const ThreadLimit limit(t);
    for (int n : {0, 1, 7, 100, 1001})
      for (int grain : {1, 8, 64}) {
        std::vector<std::atomic<int>> hits(static_cast<std::size_t>(n));
        threads::parallel_for(n, grain, [&](int i) { ++hits[static_cast<std::size_t>(i)]; });
        for (int i = 0; i < n; ++i)
          ASSERT_EQ(hits[static_cast<std::size_t>(i)].load(), 1)
              << "threads " << t << " n " << n << " grain " << grain << " index " << i;
      }
  }
}

TEST(ThreadPool, TheLowestFailingIndexIsRethrown) {
  const ThreadLimit limit(4);
  for (int repeat = 0; repeat < 50; ++repeat) {
    std::atomic<int> done{0};
    try {
      threads::parallel_for(400, 3, [&](int i) {
        if (i == 311 || i == 57 || i == 200) throw std::runtime_error(std::to_string(i));
        ++done;
      });
      FAIL() << "no exception";
    } catch (const std::runtime_error& e) {
      EXPECT_STREQ(e.what(), "57");
    }
    EXPECT_EQ(done.load(), 397);  // the other iterations still ran, as in the serial loop
  }
}

TEST(ThreadPool, ANestedLoopRunsOnItsCallersThread) {
  const ThreadLimit limit(3);
  std::vector<int> inner_threads(20, 0);
  threads::parallel_for(20, 1, [&](int i) {
    const auto me = std::this_thread::get_id();
    int others = 0;
    threads::parallel_for(50, 1, [&](int) { others += std::this_thread::get_id() != me; });
    inner_threads[static_cast<std::size_t>(i)] = others;
  });
  for (int others : inner_threads) EXPECT_EQ(others, 0);
}

double process_cpu_seconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
         1e-6 * static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

TEST(ThreadPool, WaitingWorkersTakeNoProcessorTime) {
  // Spinning workers (an OpenMP team's default) would burn a core while the caller sleeps.
  const ThreadLimit limit(2);
  std::atomic<long> sum{0};
  threads::parallel_for(1000, 10, [&](int i) { sum += i; });
  ASSERT_EQ(sum.load(), 999L * 1000 / 2);
  const double before = process_cpu_seconds();
  std::this_thread::sleep_for(std::chrono::milliseconds(400));
  EXPECT_LT(process_cpu_seconds() - before, 0.05);
}

}  // namespace
}  // namespace impactfe::test_thread_pool
