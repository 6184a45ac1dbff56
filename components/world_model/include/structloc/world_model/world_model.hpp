// The known building: straight walls (segments), corners and cylindrical
// pillars in the map frame, in metres. Built from validated elements; corners
// are also derived where two wall ends meet at 90 +- 22.5 degrees. DDS-free.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <string>
#include <vector>

#include "structloc/geometry/line.hpp"

namespace structloc::world_model {

struct Wall {
  int id = 0;
  Eigen::Vector2d a{0, 0};
  Eigen::Vector2d b{0, 0};
  geometry::Line line;  // (r, alpha) of the infinite line, map frame
  double Length() const { return (b - a).norm(); }
};

struct Corner {
  int id = 0;
  Eigen::Vector2d position{0, 0};
  bool derived = false;  // found from two wall ends rather than given
};

struct Cylinder {
  int id = 0;
  Eigen::Vector2d centre{0, 0};
  double radius = 0.0;
};

// Tolerances used when deriving corners from wall ends.
struct CornerDerivation {
  double join_tolerance_m = 0.01;                                // wall ends closer than this meet
  double angle_tolerance_rad = 22.5 * 3.14159265358979 / 180.0;  // around 90 degrees
};

// Sanity bounds on a world model. A map beyond them is almost surely in the
// wrong unit (millimetres) or hostile: coordinates of 1e8 m make wall sampling
// take minutes, and corner derivation and visibility grow with the wall count.
struct WorldLimits {
  static constexpr double kDefaultMaxAbsCoordinateM = 1e5;  // 100 km from the map origin
  static constexpr double kDefaultMaxRadiusM = 1e3;
  static constexpr size_t kDefaultMaxWalls = 250000;

  double max_abs_coordinate_m = kDefaultMaxAbsCoordinateM;  // |x| and |y| of every point
  double max_radius_m = kDefaultMaxRadiusM;                 // cylinder radius
  size_t max_walls = kDefaultMaxWalls;                      // walls per map
};

class WorldModel {
 public:
  // Validates (finite values within `limits`, walls longer than 1 mm, positive
  // radii, unique ids per kind, at least one element, at most
  // limits.max_walls walls) and derives corners. Throws std::invalid_argument
  // naming the offending element.
  WorldModel(std::string name, std::vector<Wall> walls, std::vector<Corner> corners,
             std::vector<Cylinder> cylinders, const CornerDerivation& derivation = {},
             const WorldLimits& limits = {});

  const std::string& Name() const { return name_; }
  const std::vector<Wall>& Walls() const { return walls_; }
  const std::vector<Corner>& Corners() const { return corners_; }
  const std::vector<Cylinder>& Cylinders() const { return cylinders_; }

  // Axis-aligned bounds of everything in the model: min x, min y, max x, max y.
  Eigen::Vector4d Bounds() const;

 private:
  std::string name_;
  std::vector<Wall> walls_;
  std::vector<Corner> corners_;
  std::vector<Cylinder> cylinders_;

  void DeriveCorners(const CornerDerivation& derivation);
};

// Convenience for tests and tools: a wall from two end points.
Wall MakeWall(int id, const Eigen::Vector2d& a, const Eigen::Vector2d& b);

}  // namespace structloc::world_model
