// Which walls, corners and cylinders a sensor at a given pose can see: within
// range and the scan's angular range, not hidden behind other walls or
// pillars, and (for walls) long enough and not seen too obliquely to yield
// line fits. Only these are expected by the localisation
// (thesis 3.5.3).
#pragma once

#include <utility>
#include <vector>

#include "structloc/geometry/pose2d.hpp"
#include "structloc/world_model/ray_cast.hpp"
#include "structloc/world_model/world_model.hpp"

namespace structloc::world_model {

struct VisibilityOptions {
  double min_range_m = 0.5;  // sensor's usable range
  double max_range_m = 4.0;
  // Bearings (sensor frame) of the first and last beam; a span of 2 pi or more
  // is a full circle. Default: the thesis' full-circle scanner.
  double view_min_rad = -geometry::kPi;
  double view_max_rad = geometry::kPi;
  double sample_spacing_m = 0.05;     // wall sampling step
  double min_visible_length_m = 0.3;  // shorter visible parts are not expected
  double max_incidence_rad = 75.0 * geometry::kPi / 180.0;  // grazing views do not count
  double occlusion_margin_m = 0.02;

  // A field of view centred on the sensor's x axis.
  static VisibilityOptions Centred(double field_of_view_rad);
};

struct VisibleWall {
  int index = 0;  // into WorldModel::Walls()
  double visible_length_m = 0;
  Eigen::Vector2d first{0, 0};  // visible extent along the wall (map frame)
  Eigen::Vector2d last{0, 0};
};

struct Visibility {
  std::vector<VisibleWall> walls;
  std::vector<int> corners;    // indices into WorldModel::Corners()
  std::vector<int> cylinders;  // indices into WorldModel::Cylinders()
  // Work space of ComputeVisibility: the scene's segments within range, those
  // of them that may hide (part of) one wall, and of those the ones that may
  // hide a short stretch of it.
  std::vector<int> near_segments;
  // The near segments that subtend a small angle at the sensor, sorted by the
  // bearing their angular span starts at, and the others.
  std::vector<std::pair<double, int>> narrow_segments;
  std::vector<int> wide_segments;
  std::vector<int> wall_candidates;  // near segments whose span meets one wall's
  std::vector<int> wall_occluders;
  std::vector<int> stretch_occluders;

  void Reserve(const WorldModel& world, const Scene& scene);
};

// `scene` must hold the world's own surfaces (Scene::FromWorld) and may hold more.
// Clears and fills `out` (no allocation once its vectors have grown, e.g. after
// out.Reserve(world, scene)).
void ComputeVisibility(const WorldModel& world, const Scene& scene, const geometry::Pose2D& sensor,
                       const VisibilityOptions& options, Visibility& out);

}  // namespace structloc::world_model
