#include "core/thread_pool.h"

#include <pthread.h>

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstdio>
#include <exception>
#include <mutex>
#include <new>
#include <thread>
#include <vector>

namespace impactfe::threads {

namespace {

int default_threads() {
  return std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
}

std::atomic<int> thread_limit{0};  // 0: default_threads()
thread_local bool inside_loop = false;

/// Workers block on `start_` until a loop is posted (generation_ changes), claim chunks of it,
/// and the last one to finish wakes the caller.
class Pool {
 public:
  static Pool& instance() {
    static Pool* pool = new Pool;  // never destroyed: workers may outlive static destruction
    return *pool;
  }

  void run(int n, int grain, const std::function<void(int)>& body, int threads) {
    const std::lock_guard<std::mutex> one_loop(run_mutex_);  // loops of several callers queue
    std::unique_lock<std::mutex> lock(mutex_);
    while (static_cast<int>(workers_->size()) < threads - 1)
      workers_->emplace_back([this, index = static_cast<int>(workers_->size())] { work(index); });
    body_ = &body;
    n_ = n;
    grain_ = grain;
    next_.store(0);
    failed_at_ = n;
    failure_ = nullptr;
    helpers_ = threads - 1;
    joined_ = 0;
    open_ = true;
    ++generation_;
    lock.unlock();
    start_.notify_all();
    claim();
    // Every chunk is claimed: close the loop to workers that have not joined it yet (a busy
    // machine may not run them for milliseconds; the loop never waits for them), and wait only
    // for those finishing a chunk.
    lock.lock();
    open_ = false;
    done_.wait(lock, [this] { return joined_ == 0; });
    body_ = nullptr;
    if (failure_) std::rethrow_exception(failure_);
  }

  /// After fork() the child has the calling thread only: forget the parent's workers (their
  /// std::thread objects are leaked, never joined) and start afresh.
  void forget_after_fork() {
    new (&run_mutex_) std::mutex;
    new (&mutex_) std::mutex;
    new (&start_) std::condition_variable;
    new (&done_) std::condition_variable;
    workers_ = new std::vector<std::thread>;
    joined_ = 0;
    open_ = false;
  }

 private:
  Pool() : workers_(new std::vector<std::thread>) {
    pthread_atfork(nullptr, nullptr, [] { instance().forget_after_fork(); });
  }

  void work(int index) {
    unsigned long seen = 0;
    std::unique_lock<std::mutex> lock(mutex_);
    for (;;) {
      start_.wait(lock, [&] { return generation_ != seen; });
      seen = generation_;
      // Too late (the caller finished the loop alone), or fewer threads wanted for it.
      if (!open_ || index >= helpers_) continue;
      ++joined_;
      lock.unlock();
      inside_loop = true;
      claim();
      inside_loop = false;
      lock.lock();
      if (--joined_ == 0 && !open_) done_.notify_one();
    }
  }

  void claim() {
    for (;;) {
      const int first = next_.fetch_add(grain_);
      if (first >= n_) return;
      const int last = std::min(n_, first + grain_);
      for (int i = first; i < last; ++i) {
        try {
          (*body_)(i);
        } catch (...) {
          const std::lock_guard<std::mutex> guard(failure_mutex_);
          if (i < failed_at_) {
            failed_at_ = i;
            failure_ = std::current_exception();
          }
        }
      }
    }
  }

  std::mutex run_mutex_;
  std::mutex mutex_;
  std::condition_variable start_, done_;
  std::vector<std::thread>* workers_;
  const std::function<void(int)>* body_ = nullptr;
  int n_ = 0, grain_ = 1;
  std::atomic<int> next_{0};
  unsigned long generation_ = 0;
  int helpers_ = 0;
  int joined_ = 0;     // workers inside the current loop
  bool open_ = false;  // the current loop still takes workers
  std::mutex failure_mutex_;
  int failed_at_ = 0;
  std::exception_ptr failure_;
};

}  // namespace

void set_max_threads(int n) {
  thread_limit.store(std::max(0, n));
}

int max_threads() {
  const int n = thread_limit.load();
  return n > 0 ? n : default_threads();
}

bool core_idle() {
  // The fourth field of /proc/loadavg: threads runnable now / threads in total.
  std::FILE* f = std::fopen("/proc/loadavg", "r");
  if (!f) return false;
  int runnable = 0;
  const bool read = std::fscanf(f, "%*s %*s %*s %d/", &runnable) == 1;
  std::fclose(f);
  return read && runnable < max_threads();
}

void parallel_for(int n, int grain, const std::function<void(int)>& body) {
  grain = std::max(1, grain);
  const int threads = std::min(max_threads(), (n + grain - 1) / grain);
  if (threads <= 1 || inside_loop) {
    for (int i = 0; i < n; ++i) body(i);
    return;
  }
  inside_loop = true;
  try {
    Pool::instance().run(n, grain, body, threads);
  } catch (...) {
    inside_loop = false;
    throw;
  }
  inside_loop = false;
}

}  // namespace impactfe::threads
