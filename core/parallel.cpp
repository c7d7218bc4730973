// The helper threads behind parallelFor (parallel.h).
#include "core/parallel.h"

#include <emmintrin.h>

#include <chrono>
#include <condition_variable>
#include <string>
#include <system_error>

#include "core/error.h"

namespace rc::detail {
namespace {

class HelperPool {
 public:
  ~HelperPool() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stopping_ = true;
    }
    wake_.notify_all();
    for (std::thread& t : threads_) t.join();
  }

  bool run(int helpers, void (*work)(void*, int), void* context) {
    if (busy_.exchange(true, std::memory_order_acquire)) return false;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      while (int(threads_.size()) < helpers) {
        const int index = int(threads_.size());
        try {
          threads_.emplace_back([this, index] { loop(index); });
        } catch (...) {
          // The helpers started wait for a later run; the pool stays usable.
          busy_.store(false, std::memory_order_release);
          threadStartFailed(index + 2, helpers + 1);
        }
      }
      work_ = work;
      context_ = context;
      wanted_ = helpers;
      running_ = helpers;
      published_.store(++generation_, std::memory_order_release);
    }
    wake_.notify_all();
    work(context, 0);
    {
      std::unique_lock<std::mutex> lock(mutex_);
      done_.wait(lock, [this] { return running_ == 0; });
    }
    busy_.store(false, std::memory_order_release);
    return true;
  }

 private:
  // A helper that has just finished spins this long for the next loop before it sleeps: a
  // frame's loops follow one another within microseconds, and waking a sleeping thread takes
  // about as long as starting one.
  static constexpr auto kSpin = std::chrono::microseconds(50);

  void loop(int index) {
    std::uint64_t seen = 0;
    std::unique_lock<std::mutex> lock(mutex_);
    for (;;) {
      if (!stopping_ && generation_ == seen) {
        lock.unlock();
        const auto until = std::chrono::steady_clock::now() + kSpin;
        for (int spin = 1; published_.load(std::memory_order_acquire) == seen; ++spin) {
          _mm_pause();
          if (spin % 64 == 0 && std::chrono::steady_clock::now() > until) break;
        }
        lock.lock();
      }
      wake_.wait(lock, [&] { return stopping_ || generation_ != seen; });
      if (stopping_) return;
      seen = generation_;
      if (index >= wanted_) continue;
      void (*work)(void*, int) = work_;
      void* context = context_;
      lock.unlock();
      work(context, index + 1);
      lock.lock();
      if (--running_ == 0) done_.notify_one();
    }
  }

  std::mutex mutex_;
  std::condition_variable wake_, done_;
  std::vector<std::thread> threads_;
  std::atomic<bool> busy_{false};
  std::atomic<std::uint64_t> published_{0};  // generation_, readable without the mutex
  // Under mutex_:
  std::uint64_t generation_ = 0;  // one more per run
  void (*work_)(void*, int) = nullptr;
  void* context_ = nullptr;
  int wanted_ = 0;   // helpers 0 .. wanted_ - 1 take part in this run
  int running_ = 0;  // of those, the ones still working
  bool stopping_ = false;
};

}  // namespace

void threadStartFailed(int worker, int workers) {
  try {
    throw;
  } catch (const std::system_error& cause) {
    throw Error(ExitCode::kIo, "cannot start worker thread " + std::to_string(worker) + " of " +
                                   std::to_string(workers) + ": " + cause.what() +
                                   " (memory or the limit on processes ran out; --threads 1 starts none)");
  }
}

bool runOnHelpers(int helpers, void (*work)(void*, int), void* context) {
  static HelperPool pool;
  return pool.run(helpers, work, context);
}

}  // namespace rc::detail
