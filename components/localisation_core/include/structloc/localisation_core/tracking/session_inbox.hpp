// Where the threads that deliver inputs (DDS listeners) leave them for the
// thread that runs a TrackingSession: they only copy into it and notify, so
// they never wait for a position update. One scan slot: a newer scan replaces
// one not yet taken (the newest wins; the replaced one is counted as dropped).
// Odometry and initial poses queue in arrival order.
#pragma once

#include <Eigen/Core>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <optional>
#include <vector>

#include "structloc/localisation_core/scan/session_scan.hpp"

namespace structloc::localisation_core {

struct StampedOdometry {
  double stamp = 0.0;
  geometry::Pose2D pose;
};

struct InitialPoseInput {
  double stamp = 0.0;
  geometry::Pose2D pose;
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Identity();
};

// Everything offered since the last take; `scan_arrived_s` is when the scan came.
struct SessionInputs {
  std::optional<SessionScan> scan;
  double scan_arrived_s = 0.0;
  uint64_t dropped = 0;
  std::vector<StampedOdometry> odometry;
  std::vector<InitialPoseInput> initial_poses;
  void Clear();
};

class SessionInbox {
 public:
  // At most this many odometry samples wait; more are counted and dropped
  // (the worker takes them every few milliseconds).
  static constexpr size_t kMaxQueuedOdometry = 4096;

  // `now`: the caller's clock (wall seconds live).
  void OfferScan(SessionScan scan, double now);
  void OfferOdometry(double stamp, const geometry::Pose2D& pose, double now);
  void OfferInitialPose(const InitialPoseInput& pose);
  // Waits until something was offered, Stop() was called or `timeout` passed,
  // then moves everything offered into `inputs` (cleared first). Returns false
  // once stopped.
  bool WaitAndTake(std::chrono::milliseconds timeout, SessionInputs& inputs);
  void Stop();

  // When the newest scan / odometry sample arrived (0: none yet).
  double LastScanArrival() const;
  double LastOdometryArrival() const;
  uint64_t OdometryOverflow() const;

 private:
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  SessionInputs inputs_;
  bool new_input_ = false;
  bool stopping_ = false;
  double last_scan_s_ = 0.0;
  double last_odometry_s_ = 0.0;
  uint64_t odometry_overflow_ = 0;
};

}  // namespace structloc::localisation_core
