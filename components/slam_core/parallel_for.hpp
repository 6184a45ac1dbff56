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
#include <system_error>
#include <thread>
#include <vector>

namespace structloc::slam_core {

// The threads ParallelFor(count, threads, ...) runs on at most (workers 0
// to this less one).
inline size_t ParallelWorkers(size_t count, int threads) {
  return std::max<size_t>(1, std::min(count, static_cast<size_t>(std::max(threads, 1))));
}

// Calls work(i, worker) for every i in [0, count), on up to
// ParallelWorkers(count, threads) threads (the calling one among them, worker
// 0; fewer when the system gives no more), `worker` telling which, for state
// of its own. Returns when all are done; if pieces threw, rethrows the
// exception of the lowest-numbered one, as a loop in order would have.
template <class Work>
void ParallelFor(size_t count, int threads, Work work) {
  const size_t workers = ParallelWorkers(count, threads);
  if (workers == 1) {
    for (size_t i = 0; i < count; ++i) work(i, 0);
    return;
  }
  std::atomic<size_t> next{0};
  std::exception_ptr failure;
  size_t failed_piece = count;
  std::mutex failure_mutex;
  const auto run = [&](size_t worker) {
    for (size_t i = next++; i < count; i = next++) {
      try {
        work(i, worker);
      } catch (...) {
        const std::lock_guard<std::mutex> lock(failure_mutex);
        if (i < failed_piece) {
          failed_piece = i;
          failure = std::current_exception();
        }
      }
    }
  };
  std::vector<std::thread> pool;
  pool.reserve(workers - 1);
  for (size_t w = 1; w < workers; ++w) {
    try {
      pool.emplace_back(run, w);
    } catch (const std::system_error&) {
      break;  // no more threads: the ones started and this one do the rest
    }
  }
  run(0);
  for (auto& t : pool) t.join();
  if (failure) std::rethrow_exception(failure);
}

}  // namespace structloc::slam_core
