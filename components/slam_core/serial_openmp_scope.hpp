// Ceres' sparse Cholesky runs through CHOLMOD (SuiteSparse 5), whose
// supernodal factorisation opens OpenMP teams of four threads whatever the
// caller asks: Ceres' num_threads does not reach it, nor does OMP_NUM_THREADS
// (the team size is written in CHOLMOD). A pose graph of a few thousand poses
// gives each team a few microseconds of work, less than it costs to wake it;
// beside SLAM's own threads on two cores, the teams' threads spent a sixth of
// a looping recording's time in the kernel. Each loop of those teams writes
// entries of its own, so the factor is the same on one thread. Internal to
// slam_core.
#pragma once

namespace structloc::slam_core::internal {

// While it lives, OpenMP parallel regions that the constructing thread opens
// run on that thread alone (OpenMP's max-active-levels set to 0, a setting of
// the calling thread in GCC's libgomp); the old setting comes back after. A
// no-op where the build has no OpenMP runtime to talk to.
class SerialOpenMpScope {
 public:
  SerialOpenMpScope();
  ~SerialOpenMpScope();
  SerialOpenMpScope(const SerialOpenMpScope&) = delete;
  SerialOpenMpScope& operator=(const SerialOpenMpScope&) = delete;

 private:
  int saved_levels_ = 0;
};

}  // namespace structloc::slam_core::internal
