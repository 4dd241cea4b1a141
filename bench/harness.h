// SPDX-License-Identifier: MIT
// What the Google Benchmark programs share: their main, with one option of its own,
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

/// The main of a benchmark program: runs the registered benchmarks with the arguments
/// except `option` (e.g. "--csv="), then `write(value)` when the option was given.
/// 1 on an argument Google Benchmark does not know, else 0.
template <class Write>
int benchmarkMain(int argc, char** argv, const char* option, Write write) {
  const std::size_t n = std::strlen(option);
  std::string value;
  std::vector<char*> args;
  for (int i = 0; i < argc; ++i) {
    if (std::strncmp(argv[i], option, n) == 0)
      value = argv[i] + n;
    else
      args.push_back(argv[i]);
  }
  int count = static_cast<int>(args.size());
  benchmark::Initialize(&count, args.data());
  if (benchmark::ReportUnrecognizedArguments(count, args.data())) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  if (!value.empty()) write(value);
  return 0;
}

}  // namespace sc_bench
