// Pillars for the map builder: in each scan, runs of points that are not
// straight but lie on a circular arc bulging towards the laser (the thesis'
// circle fit, 3.5.6, EQ 38, on the run) are pillar sightings; sightings from
// enough scans whose centres agree are one pillar, its centre the mean and its
// radius the median of theirs. A person walking by is sighted as such an arc
// scan after scan, a few centimetres on each time; where the sightings of a
// few scans agree, the scans taken before the person came or after they left
// look through that place: a pillar more scans saw through than sighted is
// dropped. Pillars that overlap are one built twice, and are merged.
// DDS-free.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "structloc/geometry/pose2d.hpp"
#include "structloc/map_building/posed_scans.hpp"
#include "structloc/world_model/world_model.hpp"

namespace structloc::map_building {

struct PillarOptions {
  bool enabled = true;
  double min_radius_m = 0.1;  // thinner arcs are legs, chair and table legs
  double max_radius_m = 0.6;
  int min_points = 6;             // points on one arc
  double max_rms_m = 0.01;        // of the points' distances to the fitted circle
  double min_line_rms_m = 0.005;  // arcs that fit a line this well are walls
  double min_arc_rad = 1.2;       // the arc must span this angle about its centre (~70 deg)
  double max_point_gap_m = 0.1;   // consecutive points farther apart end an arc
  double merge_distance_m = 0.1;  // sightings whose centres are closer are one pillar
  int min_scans = 5;              // pillars seen from fewer scans are dropped
  // A scan saw through a pillar when all its readings within half the
  // pillar's radius of its centre's bearing lie this far beyond its far side.
  double see_through_margin_m = 0.1;
  bool drop_seen_through = true;  // drop pillars more scans saw through than sighted
};

struct PillarReport {
  size_t sightings = 0;
  size_t pillars = 0;
  size_t too_few_scans = 0;
  size_t seen_through = 0;  // more scans saw through them than sighted them
  size_t merged = 0;        // overlapping another (one pillar built twice), merged into it
};

class PillarAccumulator {
 public:
  explicit PillarAccumulator(const PillarOptions& options) : options_(options) {}
  // Looks for arcs in one scan (points in the laser frame, beam order).
  void Add(uint32_t scan, const geometry::Pose2D& laser_pose,
           const std::vector<Eigen::Vector2d>& points);
  // The pillars; `scans` (those added) say which were seen through.
  std::vector<world_model::Cylinder> Pillars(const std::vector<PosedScan>& scans,
                                             PillarReport& report) const;

 private:
  struct Sighting {
    Eigen::Vector2d centre;
    double radius;
    uint32_t scan;
  };
  PillarOptions options_;
  std::vector<Sighting> sightings_;
};

}  // namespace structloc::map_building
