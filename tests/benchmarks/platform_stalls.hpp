// How often this machine stops a runnable thread, measured as cyclictest and
// hwlatdetect do: one thread per CPU, pinned, spins on the clock and counts
// the gaps in which it did not run. On a virtual machine whose host runs other
// guests such gaps of milliseconds are common, and no program on it can keep
// a millisecond bar at its 99th percentile through them; the latency
// benchmarks print these figures beside their own so that a missed bar can be
// told apart from a slow localiser.
#pragma once

#include <pthread.h>
#include <sched.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <thread>
#include <vector>

namespace structloc::testing {

struct PlatformStalls {
  int cpus = 0;
  double seconds = 0.0;  // spun on each CPU
  long over_100us = 0;   // gaps over 0.1 ms, all CPUs together
  long over_1ms = 0;     // gaps over 1 ms, all CPUs together
  double longest_ms = 0.0;
  double lost_share = 0.0;  // of the spinning time, in gaps over 0.1 ms
};

// Spins `seconds` on every CPU at once (each thread pinned to its own CPU).
inline PlatformStalls MeasurePlatformStalls(double seconds) {
  using Clock = std::chrono::steady_clock;
  const int cpus = std::max(1, static_cast<int>(sysconf(_SC_NPROCESSORS_ONLN)));
  struct PerCpu {
    long over_100us = 0, over_1ms = 0;
    double longest_ms = 0.0, lost_ms = 0.0;
  };
  std::vector<PerCpu> per_cpu(static_cast<size_t>(cpus));
  std::vector<std::thread> threads;
  for (int cpu = 0; cpu < cpus; ++cpu) {
    threads.emplace_back([&, cpu] {
      cpu_set_t set;
      CPU_ZERO(&set);
      CPU_SET(cpu, &set);
      pthread_setaffinity_np(pthread_self(), sizeof set, &set);
      PerCpu& out = per_cpu[static_cast<size_t>(cpu)];
      const auto start = Clock::now();
      auto last = start;
      for (auto now = start; now - start < std::chrono::duration<double>(seconds);
           now = Clock::now()) {
        const double gap = std::chrono::duration<double, std::milli>(now - last).count();
        last = now;
        if (gap <= 0.1) continue;
        ++out.over_100us;
        out.over_1ms += gap > 1.0;
        out.longest_ms = std::max(out.longest_ms, gap);
        out.lost_ms += gap;
      }
    });
  }
  for (auto& t : threads) t.join();
  PlatformStalls stalls;
  stalls.cpus = cpus;
  stalls.seconds = seconds;
  double lost_ms = 0.0;
  for (const auto& c : per_cpu) {
    stalls.over_100us += c.over_100us;
    stalls.over_1ms += c.over_1ms;
    stalls.longest_ms = std::max(stalls.longest_ms, c.longest_ms);
    lost_ms += c.lost_ms;
  }
  stalls.lost_share = lost_ms / (1e3 * seconds * cpus);
  return stalls;
}

inline void PrintPlatformStalls(const char* when, const PlatformStalls& s) {
  std::printf(
      "platform %s: a thread spinning alone on each of %d CPUs for %.0f s was stopped %.1f times "
      "a second per CPU for over 1 ms (%.1f for over 0.1 ms), at most %.2f ms, %.2f %% of the "
      "time\n",
      when, s.cpus, s.seconds, s.over_1ms / (s.seconds * s.cpus),
      s.over_100us / (s.seconds * s.cpus), s.longest_ms, 100.0 * s.lost_share);
}

}  // namespace structloc::testing
