// Writers for the plain recording formats structloc produces, so other tools
// read them too: CARMEN logs (ODOM and ROBOTLASER1 lines), TUM trajectories
// ("t x y z qx qy qz qw", read by evo), the calibration's encoders.csv and
// fixes.csv. DDS-free. Each writer writes to a temporary file beside its
// target (config::OutputFile) that only Close() renames onto the target, so a
// run that fails, or never reaches Close(), leaves an existing file untouched.
// `inputs` names the run's input files, which a writer refuses to replace.
// Each writer throws std::runtime_error (config::ConfigError for an unusable
// target) naming the file on I/O failure, including a failed final flush.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "structloc/config/output_file.hpp"
#include "structloc/geometry/pose2d.hpp"

namespace structloc::log_formats {

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
  explicit CarmenWriter(const std::string& path, const std::vector<std::string>& inputs = {});
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
  // Flushes and renames onto the target; throws when anything failed.
  void Flush() { file_.Flush(); }  // to disk, target not yet replaced
  void Close();

 private:
  config::OutputFile file_;
  std::ostream& out_;
};

class TumWriter {
 public:
  explicit TumWriter(const std::string& path, const std::vector<std::string>& inputs = {});
  void Pose(double t, const geometry::Pose2D& pose);
  // Flushes and renames onto the target; throws when anything failed.
  void Flush() { file_.Flush(); }  // to disk, target not yet replaced
  void Close();

 private:
  config::OutputFile file_;
  std::ostream& out_;
};

// encoders.csv: t,traction_ticks,steering_ticks
class EncodersCsvWriter {
 public:
  // `differential`: the header is t,left_ticks,right_ticks (SampleWheels).
  explicit EncodersCsvWriter(const std::string& path, const std::vector<std::string>& inputs = {},
                             bool differential = false);
  void Sample(double t, uint64_t traction_ticks, int64_t steering_ticks);
  void SampleWheels(double t, uint64_t left_ticks, uint64_t right_ticks);
  // Flushes and renames onto the target; throws when anything failed.
  void Flush() { file_.Flush(); }  // to disk, target not yet replaced
  void Close();

 private:
  config::OutputFile file_;
  std::ostream& out_;
};

// fixes.csv: t,x,y,theta[,var_x,var_y,var_theta]
class FixesCsvWriter {
 public:
  FixesCsvWriter(const std::string& path, bool with_variances,
                 const std::vector<std::string>& inputs = {});
  void Fix(double t, const geometry::Pose2D& pose, double var_x = 0, double var_y = 0,
           double var_theta = 0);
  // Flushes and renames onto the target; throws when anything failed.
  void Flush() { file_.Flush(); }  // to disk, target not yet replaced
  void Close();

 private:
  config::OutputFile file_;
  std::ostream& out_;
  bool with_variances_;
};

}  // namespace structloc::log_formats
