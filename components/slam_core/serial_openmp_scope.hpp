// Ceres' sparse Cholesky runs through CHOLMOD (SuiteSparse 5), whose
// supernodal factorisation opens OpenMP teams of four threads whatever the
// caller asks: Ceres' num_threads does not reach it, nor does OMP_NUM_THREADS
// (the team size is written in CHOLMOD). A pose graph of a thousand or two
// poses gives each team a few microseconds of work, less than it costs to
// wake it; beside SLAM's own threads on two cores, the teams' wake-ups took
// 15 % of a looping recording's CPU time, in the kernel. Each loop of those
// teams writes entries of its own, so the factor is the same on one thread.
// Internal to slam_core.
#pragma once

namespace structloc::slam_core::internal {

// While it lives, OpenMP parallel regions that the constructing thread opens
// run on that thread alone (OpenMP's max-active-levels set to 0); the old
// setting comes back after. In GCC 12's libgomp (Debian 12) the setting is
// the calling thread's own; in a libgomp that keeps it for the whole process,
// two threads solving at once could leave it at 0, which would only keep
// other OpenMP code serial too. A no-op where the build has no libgomp to
// talk to.
class SerialOpenMpScope {
 public:
  SerialOpenMpScope();
  ~SerialOpenMpScope();
  SerialOpenMpScope(const SerialOpenMpScope&) = delete;
  SerialOpenMpScope& operator=(const SerialOpenMpScope&) = delete;

 private:
  [[maybe_unused]] int saved_levels_ = 0;  // unused without libgomp
};

}  // namespace structloc::slam_core::internal
