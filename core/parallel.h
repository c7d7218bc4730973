// A minimal parallel-for over an index range. Work items are handed out dynamically, but
// every caller writes disjoint outputs per item, so results never depend on the thread count
// or on scheduling (STYLE.md: outputs bit-identical for 1 and N threads).
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

// Runs work() on the calling thread and on `helpers` threads kept from call to call (started
// and joined per call, a thread cost about 35 to 40 us, and a frame runs four parallel
// loops), returning when every one of them has returned. work() must not throw. Returns false
// without running anything when another call holds the pool (a parallel loop started inside
// one, or from another thread): the caller then starts threads of its own.
bool runOnHelpers(int helpers, void (*work)(void*), void* context);

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
  std::exception_ptr failure;
  std::mutex failureMutex;
  auto worker = [&] {
    for (int i = next.fetch_add(1); i < count; i = next.fetch_add(1)) {
      try {
        fn(i);
      } catch (...) {
        std::lock_guard<std::mutex> lock(failureMutex);
        if (!failure) failure = std::current_exception();
        next.store(count);
      }
    }
  };
  const auto run = [](void* context) { (*static_cast<decltype(worker)*>(context))(); };
  if (!detail::runOnHelpers(threads - 1, run, &worker)) {
    std::vector<std::thread> pool;
    pool.reserve(threads - 1);
    for (int t = 1; t < threads; ++t) pool.emplace_back(worker);
    worker();
    for (auto& thread : pool) thread.join();
  }
  if (failure) std::rethrow_exception(failure);
}

// Calls fn(i) for every i in [0, count) as parallelFor does, but each thread takes one
// contiguous run of indices: for items that write interleaved parts of a shared array, where
// neighbouring items on different threads would share cache lines.
template <typename Fn>
void parallelForContiguous(int count, int threads, Fn&& fn) {
  const int parts = std::min(resolveThreadCount(threads), count);
  parallelFor(parts, parts, [&](int part) {
    const int end = int(std::int64_t(count) * (part + 1) / parts);
    for (int i = int(std::int64_t(count) * part / parts); i < end; ++i) fn(i);
  });
}

}  // namespace rc
