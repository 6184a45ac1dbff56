// The scans a robot without a pose saw on its last metres, for the global
// localiser: one scan of a 180 deg laser often fits two places of a building
// equally well (a corridor seen from either end, rooms alike), while the
// same scan with the ones taken a few metres before it, placed by odometry,
// fits one. Keeps a few scans spaced by the distance or turn between them
// and hands them back as Readings in the frame of the newest, each point with
// the place it was seen from. Odometry drifts little over a few metres (1.5 %
// of scale and 0.3 deg/m of heading give 6 cm and 1.2 deg over 4 m); a robot
// carried away breaks the chain, so the caller clears it then. DDS-free.
#pragma once

#include <Eigen/Core>
#include <deque>
#include <vector>

#include "structloc/geometry/pose2d.hpp"
#include "structloc/localisation_core/global/global_localiser.hpp"

namespace structloc::localisation_core {

struct RecentScansOptions {
  int max_scans = 10;          // scans kept, the newest included; 1: the newest alone
  double max_travel_m = 4.0;   // odometric path from the oldest kept scan to the newest
  double min_spacing_m = 0.3;  // a scan is kept when this far from the last kept ...
  double min_turn_rad = 15.0 * geometry::kPi / 180.0;  // ... or turned this much
};

class RecentScans {
 public:
  // Throws std::invalid_argument naming the option when one is out of range.
  explicit RecentScans(const RecentScansOptions& options = {});

  // A scan's points (laser frame) and the laser's odometric pose when it was
  // taken; non-finite points are left out. False, and every scan forgotten,
  // when the pose is not finite (the chain of odometry is broken).
  bool Add(const std::vector<Eigen::Vector2d>& points, const geometry::Pose2D& laser_odometry);
  // The newest scan's points and those of the kept scans before it, in the
  // newest laser's frame; empty before the first Add.
  Readings InNewestFrame() const;
  // Adds the scan and gives the readings to search for it: InNewestFrame(),
  // or the scan alone when its pose is not finite.
  Readings WithScan(const std::vector<Eigen::Vector2d>& points,
                    const geometry::Pose2D& laser_odometry);
  // How many scans InNewestFrame() combines.
  size_t Scans() const;
  void Clear();

 private:
  struct Scan {
    std::vector<Eigen::Vector2d> points;
    geometry::Pose2D pose;  // laser, odometry frame
  };
  bool FarApart(const geometry::Pose2D& a, const geometry::Pose2D& b) const;
  std::vector<const Scan*> Combined() const;  // newest first

  RecentScansOptions options_;
  std::deque<Scan> kept_;  // oldest first, each far apart from the one before
  Scan newest_;
  bool has_newest_ = false;
};

}  // namespace structloc::localisation_core
