// Where one scan's update spent its time, stage by stage, so that a user can
// see which step of the pipeline a slow update came from (`structloc replay
// --timings`, the benchmarks): the position update's own steps (thesis 3.4-3.6),
// the whole-scan check and the local search of the tracker around it, and the
// whole update as wall time and as the thread's own CPU time (which a host
// taking the CPU away does not inflate). DDS-free.
#pragma once

#include <array>
#include <cstddef>

namespace structloc::localisation_core {

enum class Stage {
  kPrefilter,    // range gate, de-skew, unsupported points, thinning (3.4)
  kExpectation,  // what the map shows from the prior: visibility, expected features (3.5.3)
  kLineFit,      // sliding least-squares line fits (3.5.2)
  kExtraction,   // every feature kind: clustering, pairing, gating (3.5)
  kSolve,        // the pose from the matched features, its gates (3.6)
  kCheck,        // the whole-scan check of the correction against the map
  kSearch,       // a local search of a tracker that lost the map (re-acquisition)
  kCount
};

inline constexpr std::array<const char*, static_cast<size_t>(Stage::kCount)> kStageNames = {
    "prefilter", "expectation", "line fits", "extraction", "solve", "whole-scan check", "search"};

struct StageTimings {
  std::array<double, static_cast<size_t>(Stage::kCount)> us{};  // wall time of each stage
  double total_us = 0.0;                                        // the whole update, wall time
  double total_cpu_us = 0.0;  // the whole update, the thread's CPU time

  double& operator[](Stage s) { return us[static_cast<size_t>(s)]; }
  double operator[](Stage s) const { return us[static_cast<size_t>(s)]; }
};

// The calling thread's CPU time so far, in microseconds.
double ThreadCpuMicroseconds();

}  // namespace structloc::localisation_core
