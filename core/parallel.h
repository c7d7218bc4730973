// Minimal parallel loops: parallelFor over an index range, and parallelForQueues over one queue
// of items per worker (for loops whose items should run on the core that made their inputs).
// Work items are handed out dynamically, but every caller writes disjoint outputs per item, so
// results never depend on the thread count or on scheduling (STYLE.md: outputs bit-identical
// for 1 and N threads).
#pragma once

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace rc {

// The number of worker threads to use when the user asks for 0 ("all cores").
inline int resolveThreadCount(int requested) {
  if (requested > 0) return requested;
  return std::max(1u, std::thread::hardware_concurrency());
}

namespace detail {

// Runs work(context, 0) on the calling thread and work(context, w) for w in [1, helpers] on
// `helpers` threads kept from call to call (started and joined per call, a thread cost about
// 35 to 40 us, and a frame runs four parallel loops), returning when every one of them has
// returned. work() must not throw. Throws (threadStartFailed) where a helper cannot be
// started, before running anything. Returns false without running anything when another call
// holds the pool (a parallel loop started inside one, or from another thread): the caller
// then starts threads of its own.
bool runOnHelpers(int helpers, void (*work)(void*, int), void* context);

// Called in the catch block where a thread could not be started. A std::system_error (memory
// or the process limit ran out) is thrown again as an rc::Error with exit code 4 naming the
// thread: "cannot start worker thread 2 of 2: ...". Anything else (std::bad_alloc, where the
// thread's state could not be allocated) is rethrown as it is.
[[noreturn]] void threadStartFailed(int worker, int workers);

// Runs worker(w) for every w in [0, threads), worker 0 on the calling thread. Where a thread
// cannot be started, whatever std::thread throws, the ones already started finish (each
// worker takes what work is left, so they end) and are joined before threadStartFailed
// throws: a std::thread destroyed unjoined would call std::terminate.
template <typename Worker>
void runWorkers(int threads, Worker& worker) {
  const auto run = [](void* context, int w) { (*static_cast<Worker*>(context))(w); };
  if (!runOnHelpers(threads - 1, run, &worker)) {
    std::vector<std::thread> pool;
    pool.reserve(std::size_t(threads - 1));
    for (int w = 1; w < threads; ++w) {
      try {
        pool.emplace_back(worker, w);
      } catch (...) {
        for (auto& thread : pool) thread.join();
        threadStartFailed(w + 1, threads);
      }
    }
    worker(0);
    for (auto& thread : pool) thread.join();
  }
}

// The first exception any worker throws, rethrown on the calling thread once all stop.
class FirstFailure {
 public:
  template <typename Fn>
  void run(Fn&& fn) {
    try {
      fn();
    } catch (...) {
      std::lock_guard<std::mutex> lock(mutex_);
      if (!failure_) failure_ = std::current_exception();
      failed_.store(true);
    }
  }
  bool failed() const { return failed_.load(std::memory_order_relaxed); }
  void rethrow() const {
    if (failure_) std::rethrow_exception(failure_);
  }

 private:
  std::mutex mutex_;
  std::exception_ptr failure_;
  std::atomic<bool> failed_{false};
};

}  // namespace detail

// Calls fn(i) for every i in [0, count) on up to `threads` threads. The first exception
// thrown by any call is rethrown on the calling thread after all workers stop.
template <typename Fn>
void parallelFor(int count, int threads, Fn&& fn) {
  threads = std::min(resolveThreadCount(threads), std::max(count, 1));
  if (threads <= 1) {
    for (int i = 0; i < count; ++i) fn(i);
    return;
  }
  std::atomic<int> next{0};
  detail::FirstFailure failure;
  auto worker = [&](int) {
    for (int i = next.fetch_add(1); i < count; i = next.fetch_add(1)) {
      failure.run([&] { fn(i); });
      if (failure.failed()) next.store(count);
    }
  };
  detail::runWorkers(threads, worker);
  failure.rethrow();
}

// Work handed out in queues, one per worker: worker w (0 is the calling thread) calls
// fn(item, w) for the items of queues[w] from the front, then helps empty the other queues
// from their back. For a loop whose items read what worker w wrote in an earlier loop: they
// run on the core whose caches hold it, and the stealing still keeps every core busy. As with
// parallelFor, callers write disjoint outputs per item, so results never depend on which
// worker ran an item; fn learns w only to say where its outputs were written. Exceptions as
// parallelFor.
template <typename Fn>
void parallelForQueues(const std::vector<std::vector<int>>& queues, Fn&& fn) {
  const int count = int(queues.size());
  std::size_t items = 0;
  for (const auto& queue : queues) items += queue.size();
  const int workers = int(std::min(queues.size(), items));  // the others' queues get taken
  if (workers <= 1) {
    for (const auto& queue : queues) {
      for (int item : queue) fn(item, 0);
    }
    return;
  }
  // Per queue, the next item from the front (low 32 bits) and one past the last from the
  // back (high 32 bits), in one word so that the owner and a thief never take the same item.
  struct alignas(64) Cursor {
    std::atomic<std::uint64_t> span;
  };
  std::vector<Cursor> cursors(queues.size());
  for (std::size_t q = 0; q < queues.size(); ++q) cursors[q].span.store(std::uint64_t(queues[q].size()) << 32);
  const auto take = [&](int q, bool fromBack) {
    std::atomic<std::uint64_t>& span = cursors[std::size_t(q)].span;
    std::uint64_t s = span.load();
    for (;;) {
      const auto front = std::uint32_t(s), back = std::uint32_t(s >> 32);
      if (front >= back) return -1;
      const std::uint64_t next = fromBack ? (std::uint64_t(back - 1) << 32 | front) : s + 1;
      if (span.compare_exchange_weak(s, next)) return queues[std::size_t(q)][fromBack ? back - 1 : front];
    }
  };
  detail::FirstFailure failure;
  auto worker = [&](int w) {
    for (int k = 0; k < count && !failure.failed(); ++k) {
      const int q = (w + k) % count;
      for (int item = take(q, k > 0); item >= 0 && !failure.failed(); item = take(q, k > 0)) {
        failure.run([&] { fn(item, w); });
      }
    }
  };
  detail::runWorkers(workers, worker);
  failure.rethrow();
}

// Splits [0, count) into `parts` contiguous runs of near-equal length, one queue each.
inline std::vector<std::vector<int>> contiguousQueues(int count, int parts) {
  std::vector<std::vector<int>> queues(std::size_t(std::max(parts, 1)));
  for (std::size_t part = 0; part < queues.size(); ++part) {
    const int begin = int(std::int64_t(count) * std::int64_t(part) / std::int64_t(queues.size()));
    const int end = int(std::int64_t(count) * std::int64_t(part + 1) / std::int64_t(queues.size()));
    for (int i = begin; i < end; ++i) queues[part].push_back(i);
  }
  return queues;
}

}  // namespace rc
