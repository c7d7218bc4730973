// Running code where memory runs out, to see that it fails with a named rc::Error: for a death
// test (EXPECT_EXIT), since the limit holds for the whole process.
#pragma once

#include <sys/resource.h>

#include <cstdio>
#include <cstdlib>

#include "core/error.h"

// Whether AddressSanitizer is built in (GCC says so by a macro, Clang by __has_feature): its
// shadow memory does not run in a limited address space, so such tests skip there.
#if defined(__SANITIZE_ADDRESS__)
#define RC_TEST_UNDER_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define RC_TEST_UNDER_ASAN 1
#endif
#endif

namespace rc::testing {

// Limits the address space to what the process maps now plus `headroomBytes` (1 MB: small
// allocations fit, a thread's stack does not), runs `body`, and prints the message of the
// rc::Error it throws ("the body ran" when none). Then lifts the limit and exits with that
// error's exit code (0 when none), or 100 when `then()`, run after the limit is lifted,
// returns false. Anything else `body` throws escapes and aborts.
template <typename Body, typename Then>
[[noreturn]] void exitAfterRunningOutOfMemory(long headroomBytes, Body&& body, Then&& then) {
  rlimit limit{};
  getrlimit(RLIMIT_AS, &limit);
  const rlimit lifted = limit;
  long mappedKb = 0;
  std::FILE* status = std::fopen("/proc/self/status", "r");
  char line[256];
  while (status && std::fgets(line, sizeof line, status)) std::sscanf(line, "VmSize: %ld kB", &mappedKb);
  if (status) std::fclose(status);
  limit.rlim_cur = rlim_t(mappedKb * 1024 + headroomBytes);
  setrlimit(RLIMIT_AS, &limit);
  int code = 0;
  try {
    body();
    std::fprintf(stderr, "the body ran\n");
  } catch (const Error& e) {
    std::fprintf(stderr, "%s\n", e.what());
    code = int(e.code());
  }
  setrlimit(RLIMIT_AS, &lifted);
  if (!then()) code = 100;
  std::fflush(stderr);
  std::_Exit(code);
}

}  // namespace rc::testing
