// Writers for the plain recording formats structloc produces, so other tools
// read them too: CARMEN logs (ODOM and ROBOTLASER1 lines), TUM trajectories
// ("t x y z qx qy qz qw", read by evo), the calibration's encoders.csv and
// fixes.csv. DDS-free. Each writer throws std::runtime_error on I/O failure.
#pragma once

#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

#include "pose2d.hpp"

namespace structloc::logs {

// Laser geometry as CARMEN's ROBOTLASER1 line carries it.
struct CarmenLaser {
  double start_angle = 0.0;
  double field_of_view = 0.0;
  double angular_resolution = 0.0;
  double max_range = 0.0;
  double accuracy = 0.01;
};

class CarmenWriter {
 public:
  explicit CarmenWriter(const std::string& path);
  // ODOM x y theta tv rv accel ipc_timestamp hostname logger_timestamp
  void Odometry(double t, const geometry::Pose2D& pose, double tv, double rv);
  // ROBOTLASER1 with laser and robot poses in the odometry frame; non-finite
  // ranges are written as max_range + 1 ("no return", as CARMEN tools expect).
  void RobotLaser(double t, const CarmenLaser& laser, const std::vector<float>& ranges,
                  const geometry::Pose2D& laser_pose, const geometry::Pose2D& robot_pose, double tv,
                  double rv);
  void Comment(const std::string& text);
  // PARAM name value (CARMEN's parameter lines).
  void Param(const std::string& name, double value);
  void Close();

 private:
  std::ofstream out_;
  std::string path_;
};

class TumWriter {
 public:
  explicit TumWriter(const std::string& path);
  void Pose(double t, const geometry::Pose2D& pose);
  void Close();

 private:
  std::ofstream out_;
  std::string path_;
};

// encoders.csv: t,traction_ticks,steering_ticks
class EncodersCsvWriter {
 public:
  explicit EncodersCsvWriter(const std::string& path);
  void Sample(double t, uint64_t traction_ticks, int64_t steering_ticks);
  void Close();

 private:
  std::ofstream out_;
  std::string path_;
};

// fixes.csv: t,x,y,theta[,var_x,var_y,var_theta]
class FixesCsvWriter {
 public:
  FixesCsvWriter(const std::string& path, bool with_variances);
  void Fix(double t, const geometry::Pose2D& pose, double var_x = 0, double var_y = 0,
           double var_theta = 0);
  void Close();

 private:
  std::ofstream out_;
  std::string path_;
  bool with_variances_;
};

}  // namespace structloc::logs
