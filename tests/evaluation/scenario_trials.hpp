// What the scenario evaluations (global start, kidnapping) share: their
// command line "SCENARIO.xml [COUNT] [--seed N] [--check] [--start SCAN]",
// the median they print and the thread's CPU clock they time with.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <optional>
#include <string>
#include <vector>

namespace structloc::testing {

// The calling thread's CPU time so far, in microseconds.
inline double ThreadCpuUs() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return 1e6 * static_cast<double>(t.tv_sec) + 1e-3 * static_cast<double>(t.tv_nsec);
}

struct TrialArguments {
  std::string scenario;
  size_t count = 0;  // starts or teleports
  unsigned seed = 1;
  bool check = false;
  std::optional<size_t> only_start;  // --start: every trial at this scan
};

// Nullopt (after printing `usage`) when there is no scenario.
inline std::optional<TrialArguments> ParseTrialArguments(int argc, char** argv,
                                                         size_t default_count, const char* usage) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s\n", usage);
    return std::nullopt;
  }
  TrialArguments a;
  a.scenario = argv[1];
  a.count = default_count;
  for (int i = 2; i < argc; ++i) {
    if (std::strcmp(argv[i], "--check") == 0) {
      a.check = true;
    } else if (std::strcmp(argv[i], "--start") == 0 && i + 1 < argc) {
      a.only_start = std::stoul(argv[++i]);
    } else if (std::strcmp(argv[i], "--seed") == 0 && i + 1 < argc) {
      a.seed = static_cast<unsigned>(std::stoul(argv[++i]));
    } else {
      a.count = std::stoul(argv[i]);
    }
  }
  return a;
}

inline double Median(std::vector<double> v) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace structloc::testing
