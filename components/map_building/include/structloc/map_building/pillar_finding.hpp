// Pillars for the map builder: in each scan, runs of points that are not
// straight but lie on a circular arc bulging towards the laser (the thesis'
// circle fit, 3.5.6, EQ 38, on the run) are pillar sightings; sightings from
// enough scans whose centres agree are one pillar, its centre the mean and its
// radius the median of theirs. DDS-free.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "structloc/geometry/pose2d.hpp"
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
};

struct PillarReport {
  size_t sightings = 0;
  size_t pillars = 0;
  size_t too_few_scans = 0;
};

class PillarAccumulator {
 public:
  explicit PillarAccumulator(const PillarOptions& options) : options_(options) {}
  // Looks for arcs in one scan (points in the laser frame, beam order).
  void Add(uint32_t scan, const geometry::Pose2D& laser_pose,
           const std::vector<Eigen::Vector2d>& points);
  std::vector<world_model::Cylinder> Pillars(PillarReport& report) const;

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
