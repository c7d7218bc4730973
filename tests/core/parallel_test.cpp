// parallelFor: every index once, exceptions brought back, and the helper threads it keeps
// between calls shared safely by nested and concurrent loops.
#include "core/parallel.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <thread>
#include <vector>

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

}  // namespace
}  // namespace rc
