// SPDX-License-Identifier: MIT
// What the Google Benchmark programs share: their main with one option of its own,
// and the clocks they time queries with.
#pragma once

#include <benchmark/benchmark.h>
#include <time.h>

#include <chrono>
#include <cstring>
#include <string>
#include <vector>

namespace sc_bench {

using Clock = std::chrono::steady_clock;

inline double seconds(Clock::time_point t0, Clock::time_point t1) {
  return std::chrono::duration<double>(t1 - t0).count();
}

/// CPU time of this thread: the cost of a query, robust to the machine's other load.
inline double threadCpuSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

/// Runs the registered benchmarks with the arguments except `option` (e.g. "--csv="),
/// whose value it returns in `value` ("" when absent). False on an argument Google
/// Benchmark does not know.
inline bool runBenchmarks(int argc, char** argv, const char* option, std::string& value) {
  const std::size_t n = std::strlen(option);
  std::vector<char*> args;
  for (int i = 0; i < argc; ++i) {
    if (std::strncmp(argv[i], option, n) == 0)
      value = argv[i] + n;
    else
      args.push_back(argv[i]);
  }
  int count = static_cast<int>(args.size());
  benchmark::Initialize(&count, args.data());
  if (benchmark::ReportUnrecognizedArguments(count, args.data())) return false;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return true;
}

}  // namespace sc_bench
