// A CARMEN log written from live streams (structloc record): odometry and
// laser scans arrive on their own threads, out of step with each other, and
// the log must hold them in time order, each scan with the robot's odometric
// pose at its stamp (interpolated) and the laser's pose through the mounting,
// so that replay, map building and calibration read it as they read any
// CARMEN log. Lines are held until odometry has run `hold_s` past them (a
// scan delivered late still finds its place), then written in stamp order;
// Finish writes everything still held, so a stop loses nothing received. A
// scan the odometry does not reach on both sides (before the first sample,
// or after the last at the end) takes the nearest sample, and is counted. Not
// thread-safe: the caller serialises. DDS-free.
#pragma once

#include <cstddef>
#include <deque>
#include <optional>
#include <string>
#include <vector>

#include "structloc/log_formats/recording_writers.hpp"

namespace structloc::log_formats {

struct CarmenRecordingOptions {
  double hold_s = 0.5;              // lines wait until odometry is this far past them
  size_t max_held_scans = 4096;     // beyond: the oldest are written with what odometry there is
  double odometry_history_s = 5.0;  // kept for scans that come late
};

struct CarmenRecordingStats {
  size_t scans = 0;                   // ROBOTLASER1 lines written
  size_t odometry = 0;                // ODOM lines written
  size_t scans_nearest_odometry = 0;  // odometry did not reach them on both sides
  size_t scans_late = 0;  // came after lines younger than them were written (out of order)
  size_t rejected = 0;    // non-finite stamps or poses: never written
};

class CarmenRecording {
 public:
  // `writer` must outlive the recording. `mount`: the laser on the robot,
  // when known now (else SetMount before the first scan is written; scans
  // wait for it until Finish, which writes them with a zero mount).
  CarmenRecording(CarmenWriter& writer, std::optional<geometry::Pose2D> mount,
                  const CarmenRecordingOptions& options = {});

  void SetMount(const geometry::Pose2D& mount);
  bool HasMount() const { return mount_.has_value(); }
  // `tv`, `rv`: forward and turn rates (m/s, rad/s) as the odometry gives them.
  void AddOdometry(double stamp, const geometry::Pose2D& pose, double tv, double rv);
  void AddScan(double stamp, const CarmenLaser& laser, std::vector<float> ranges);
  // Writes what is ready (call after adding).
  void WriteReady();
  // Writes everything held (the end of the recording). Returns false when
  // scans had to be written without a known mount.
  bool Finish();
  const CarmenRecordingStats& Stats() const { return stats_; }

 private:
  struct Odometry {
    double stamp;
    geometry::Pose2D pose;
    double tv, rv;
  };
  struct Scan {
    double stamp;
    CarmenLaser laser;
    std::vector<float> ranges;
  };
  // Writes held lines up to `until` (inclusive), in stamp order.
  void WriteUntil(double until);
  void WriteScan(const Scan& scan);
  // The odometry at `t` from what was seen (interpolated; the nearest sample
  // beyond), nullopt before any.
  std::optional<Odometry> OdometryAt(double t, bool* nearest) const;

  CarmenWriter& writer_;
  std::optional<geometry::Pose2D> mount_;
  CarmenRecordingOptions options_;
  std::deque<Odometry> held_odometry_;  // not yet written, in stamp order
  std::deque<Scan> held_scans_;         // not yet written, in stamp order
  std::deque<Odometry> history_;        // written or held, for interpolation
  std::optional<double> newest_odometry_;
  double written_until_ = -1e300;  // stamp of the last line written
  CarmenRecordingStats stats_;
};

}  // namespace structloc::log_formats
