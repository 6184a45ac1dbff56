// Independent pieces of work on a few threads, for the SLAM front end's
// matches (a keyframe's loop candidates, the scans between keyframes, the
// latency estimate's pairs): each piece writes its own result, which the
// caller then reads in order, so the outcome does not depend on the number of
// threads or on which thread ran what. DDS-free.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace structloc::slam_core {

// Calls work(i, worker) for every i in [0, count), on min(count, threads)
// threads (the calling one among them), `worker` telling which (from 0, the
// calling one), for state of its own; returns when all are done, rethrowing
// the first exception a piece threw.
template <class Work>
void ParallelFor(size_t count, int threads, Work work) {
  const size_t helpers = std::min(count, static_cast<size_t>(std::max(threads, 1))) - (count > 0);
  if (helpers == 0) {
    for (size_t i = 0; i < count; ++i) work(i, 0);
    return;
  }
  std::atomic<size_t> next{0};
  std::exception_ptr failure;
  std::mutex failure_mutex;
  const auto run = [&](size_t worker) {
    for (size_t i = next++; i < count; i = next++) {
      try {
        work(i, worker);
      } catch (...) {
        const std::lock_guard<std::mutex> lock(failure_mutex);
        if (!failure) failure = std::current_exception();
      }
    }
  };
  std::vector<std::thread> pool;
  pool.reserve(helpers);
  for (size_t h = 1; h <= helpers; ++h) pool.emplace_back(run, h);
  run(0);
  for (auto& t : pool) t.join();
  if (failure) std::rethrow_exception(failure);
}

}  // namespace structloc::slam_core
