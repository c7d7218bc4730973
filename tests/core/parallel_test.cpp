// parallelFor and parallelForQueues: every index once, exceptions brought back, the helper
// threads they keep between calls shared safely by nested and concurrent loops, and a thread
// that cannot start named.
#include "core/parallel.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <mutex>
#include <new>
#include <stdexcept>
#include <thread>
#include <utility>
#include <vector>

#include "core/error.h"
#include "tests/limited_memory.h"

namespace rc {
namespace {

// How many times each index was visited.
std::vector<int> visits(int count, int threads) {
  std::vector<std::atomic<int>> seen(count);
  parallelFor(count, threads, [&](int i) { seen[i].fetch_add(1); });
  std::vector<int> out;
  for (const auto& s : seen) out.push_back(s.load());
  return out;
}

TEST(ParallelFor, VisitsEveryIndexOnceForAnyThreadCount) {
  for (int threads : {1, 2, 3, 8, 2}) {  // the pool grows, then serves a smaller request
    for (int count : {0, 1, 2, 7, 1000}) {
      EXPECT_EQ(visits(count, threads), std::vector<int>(count, 1)) << count << " items, " << threads << " threads";
    }
  }
}

// Runs `loop` where no thread's stack fits, then checks that a loop on 2 threads still visits
// every index (tests/limited_memory.h).
template <typename Loop>
[[noreturn]] void failToStartAThread(Loop&& loop) {
  testing::exitAfterRunningOutOfMemory(1 << 20, loop, [] { return visits(100, 2) == std::vector<int>(100, 1); });
}

// A thread that cannot be started (memory or the process limit ran out) is an rc::Error with
// exit code 4 that names it, not a std::system_error (exit 5, "internal error"), both where
// the kept helpers are started and where a nested loop starts threads of its own; the loop
// can run again once threads can start.
TEST(ParallelFor, AThreadThatCannotStartIsNamedWithExitCode4) {
#if defined(RC_TEST_UNDER_ASAN)
  GTEST_SKIP() << "the sanitizer's shadow memory does not run in a limited address space";
#endif
  GTEST_FLAG_SET(death_test_style, "threadsafe");  // a fresh process: no helper started yet
  const auto noop = [](int) {};
  EXPECT_EXIT(failToStartAThread([&] { parallelFor(8, 2, noop); }), ::testing::ExitedWithCode(4),
              "cannot start worker thread 2 of 2: .*--threads 1");
  EXPECT_EXIT(failToStartAThread([&] {
                parallelFor(2, 2, [&](int) { parallelFor(8, 2, noop); });
              }),
              ::testing::ExitedWithCode(4), "cannot start worker thread 2 of 2");
}

// A worker whose second copy throws std::bad_alloc: std::thread copies its callable into the
// state it allocates, so this is how starting a thread fails with something other than a
// std::system_error.
struct WorkerWhoseSecondCopyThrows {
  std::atomic<int>* copies;
  std::atomic<int>* runs;
  WorkerWhoseSecondCopyThrows(std::atomic<int>* c, std::atomic<int>* r) : copies(c), runs(r) {}
  WorkerWhoseSecondCopyThrows(const WorkerWhoseSecondCopyThrows& o) : copies(o.copies), runs(o.runs) {
    if (copies->fetch_add(1) == 1) throw std::bad_alloc();
  }
  WorkerWhoseSecondCopyThrows(WorkerWhoseSecondCopyThrows&&) noexcept = default;
  void operator()(int) const { runs->fetch_add(1); }
};

// Where a nested loop (the kept helpers are busy) starts threads of its own and the second
// one fails with std::bad_alloc, the first is joined and the std::bad_alloc comes back as it
// is (the CLI names it "out of memory", exit 4). Destroying the started thread unjoined would
// call std::terminate. The loops run again afterwards.
TEST(ParallelFor, AThreadThatCannotBeAllocatedJoinsTheOnesStartedAndRethrows) {
  std::atomic<int> copies{0}, runs{0};
  EXPECT_THROW(parallelFor(2, 2,
                           [&](int i) {
                             if (i != 0) return;
                             WorkerWhoseSecondCopyThrows worker(&copies, &runs);
                             detail::runWorkers(3, worker);
                           }),
               std::bad_alloc);
  EXPECT_EQ(copies.load(), 2);
  EXPECT_EQ(runs.load(), 1);  // the thread started ran and was joined; worker 0 never ran
  EXPECT_EQ(visits(100, 3), std::vector<int>(100, 1));
}

TEST(ParallelFor, RethrowsTheFirstExceptionAndStaysUsable) {
  EXPECT_THROW(parallelFor(100, 2, [](int i) {
                 if (i == 37) throw std::runtime_error("item 37");
               }),
               std::runtime_error);
  EXPECT_EQ(visits(500, 2), std::vector<int>(500, 1));
}

// A loop started inside another one, or from a second thread while the helpers are busy,
// starts threads of its own; all of them still visit every index once.
TEST(ParallelFor, NestedAndConcurrentLoopsVisitEveryIndexOnce) {
  std::vector<std::atomic<int>> inner(16 * 50);
  parallelFor(16, 2, [&](int outer) {
    parallelFor(50, 2, [&](int i) { inner[outer * 50 + i].fetch_add(1); });
  });
  for (const auto& v : inner) ASSERT_EQ(v.load(), 1);

  std::vector<int> a, b;
  std::thread other([&] {
    for (int k = 0; k < 200; ++k) a = visits(300, 2);
  });
  for (int k = 0; k < 200; ++k) b = visits(300, 2);
  other.join();
  EXPECT_EQ(a, std::vector<int>(300, 1));
  EXPECT_EQ(b, std::vector<int>(300, 1));
}

// Queues of uneven lengths (empty ones, more queues than items, one long queue), as the
// rasterizer makes them: every item runs once, on a worker in range, and a worker takes its
// own queue front to back (others take from its back, so what it ran is a prefix, in order).
TEST(ParallelForQueues, RunsEveryItemOnceAndEachWorkerItsOwnQueueInOrder) {
  const std::vector<std::vector<std::vector<int>>> shapes = {
      {},
      {{0, 1, 2}},
      {{0, 1, 2, 3, 4}, {5, 6}},
      {{}, {0, 1, 2, 3, 4, 5, 6, 7}},
      {{3}, {}, {}, {0, 1, 2}},
      {{0}, {}, {}, {}, {}, {}},
      contiguousQueues(1000, 2),
      contiguousQueues(7, 3),
      contiguousQueues(2, 8),
  };
  for (std::size_t k = 0; k < shapes.size(); ++k) {
    const auto& queues = shapes[k];
    std::size_t items = 0;
    for (const auto& q : queues) items += q.size();
    for (int round = 0; round < 20; ++round) {
      std::vector<std::atomic<int>> seen(items);
      std::mutex mutex;
      std::vector<std::pair<int, int>> runs;  // (worker, item) in the order each worker ran them
      parallelForQueues(queues, [&](int item, int worker) {
        seen[std::size_t(item)].fetch_add(1);
        std::lock_guard<std::mutex> lock(mutex);
        runs.emplace_back(worker, item);
      });
      for (std::size_t i = 0; i < items; ++i) ASSERT_EQ(seen[i].load(), 1) << "shape " << k << ", item " << i;
      for (std::size_t w = 0; w < queues.size(); ++w) {
        std::vector<int> own;  // the items of queue w that worker w ran, in its order
        for (const auto& [worker, item] : runs) {
          ASSERT_GE(worker, 0);
          ASSERT_LT(std::size_t(worker), std::max<std::size_t>(queues.size(), 1));
          if (std::size_t(worker) == w &&
              std::find(queues[w].begin(), queues[w].end(), item) != queues[w].end()) {
            own.push_back(item);
          }
        }
        const std::vector<int> prefix(queues[w].begin(), queues[w].begin() + std::ptrdiff_t(own.size()));
        EXPECT_EQ(own, prefix) << "shape " << k << ", worker " << w;
      }
    }
  }
}

TEST(ParallelForQueues, OneQueueRunsOnTheCallingThreadAsWorkerZero) {
  const auto caller = std::this_thread::get_id();
  std::vector<int> order;
  parallelForQueues(contiguousQueues(50, 1), [&](int item, int worker) {
    EXPECT_EQ(worker, 0);
    EXPECT_EQ(std::this_thread::get_id(), caller);
    order.push_back(item);
  });
  std::vector<int> expected(50);
  for (int i = 0; i < 50; ++i) expected[std::size_t(i)] = i;
  EXPECT_EQ(order, expected);
}

TEST(ParallelForQueues, RethrowsTheFirstExceptionAndStaysUsable) {
  EXPECT_THROW(parallelForQueues(contiguousQueues(100, 2),
                                 [](int item, int) {
                                   if (item == 77) throw std::runtime_error("item 77");
                                 }),
               std::runtime_error);
  std::vector<std::atomic<int>> seen(300);
  parallelForQueues(contiguousQueues(300, 2), [&](int item, int) { seen[std::size_t(item)].fetch_add(1); });
  for (const auto& s : seen) EXPECT_EQ(s.load(), 1);
}

TEST(ParallelForQueues, ContiguousQueuesSplitTheRangeInOrder) {
  EXPECT_EQ(contiguousQueues(7, 3), (std::vector<std::vector<int>>{{0, 1}, {2, 3}, {4, 5, 6}}));
  EXPECT_EQ(contiguousQueues(2, 4), (std::vector<std::vector<int>>{{}, {0}, {}, {1}}));
  EXPECT_EQ(contiguousQueues(0, 2), (std::vector<std::vector<int>>{{}, {}}));
}

}  // namespace
}  // namespace rc
