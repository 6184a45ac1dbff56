// Recording writers (see header).
#include "structloc/log_formats/recording_writers.hpp"

#include <cmath>
#include <iomanip>
#include <stdexcept>

namespace structloc::log_formats {
namespace {

void Check(std::ostream& out, const std::string& path) {
  if (!out) throw std::runtime_error(path + ": write failed");
}

}  // namespace

CarmenWriter::CarmenWriter(const std::string& path, const std::vector<std::string>& inputs)
    : file_(path, inputs), out_(file_.Stream()) {
  out_ << std::setprecision(9);
  out_ << "# CARMEN log written by structloc\n"
       << "# ODOM x y theta tv rv accel ipc_timestamp hostname logger_timestamp\n"
       << "# ROBOTLASER1 laser_type start_angle fov angular_res max_range accuracy remission_mode "
          "num_readings [range] num_remissions laser_x laser_y laser_theta robot_x robot_y "
          "robot_theta tv rv forward_safety_dist side_safety_dist turn_axis ipc_timestamp "
          "hostname logger_timestamp\n";
}

void CarmenWriter::Param(const std::string& name, double value) {
  out_ << "PARAM " << name << " " << std::scientific << std::setprecision(12) << value
       << std::defaultfloat << "\n";
}

void CarmenWriter::Comment(const std::string& text) {
  out_ << "# " << text << "\n";
}

void CarmenWriter::Odometry(double t, const geometry::Pose2D& p, double tv, double rv) {
  out_ << std::fixed << std::setprecision(6) << "ODOM " << p.x << " " << p.y << " " << p.theta
       << " " << tv << " " << rv << " 0 " << t << " structloc " << t << "\n";
  Check(out_, file_.Path());
}

void CarmenWriter::RobotLaser(double t, const CarmenLaser& l, const std::vector<float>& ranges,
                              const geometry::Pose2D& lp, const geometry::Pose2D& rp, double tv,
                              double rv) {
  out_ << std::fixed << std::setprecision(6) << "ROBOTLASER1 0 " << l.start_angle << " "
       << l.field_of_view << " " << l.angular_resolution << " " << l.max_range << " " << l.accuracy
       << " 0 " << ranges.size();
  out_ << std::setprecision(3);
  for (float r : ranges)
    out_ << " " << (std::isfinite(r) ? static_cast<double>(r) : l.max_range + 1.0);
  out_ << std::setprecision(6) << " 0 " << lp.x << " " << lp.y << " " << lp.theta << " " << rp.x
       << " " << rp.y << " " << rp.theta << " " << tv << " " << rv << " 0 0 0 " << t
       << " structloc " << t << "\n";
  Check(out_, file_.Path());
}

void CarmenWriter::Close() {
  file_.Commit();
}

TumWriter::TumWriter(const std::string& path, const std::vector<std::string>& inputs)
    : file_(path, inputs), out_(file_.Stream()) {
  out_ << std::setprecision(9);
  out_ << "# timestamp x y z qx qy qz qw\n";
}

void TumWriter::Pose(double t, const geometry::Pose2D& p) {
  out_ << std::fixed << std::setprecision(6) << t << " " << std::setprecision(6) << p.x << " "
       << p.y << " 0 0 0 " << std::setprecision(9) << std::sin(0.5 * p.theta) << " "
       << std::cos(0.5 * p.theta) << "\n";
  Check(out_, file_.Path());
}

void TumWriter::Close() {
  file_.Commit();
}

EncodersCsvWriter::EncodersCsvWriter(const std::string& path,
                                     const std::vector<std::string>& inputs, bool differential)
    : file_(path, inputs), out_(file_.Stream()) {
  out_ << std::setprecision(9);
  out_ << (differential ? "t,left_ticks,right_ticks\n" : "t,traction_ticks,steering_ticks\n");
}

void EncodersCsvWriter::SampleWheels(double t, uint64_t left, uint64_t right) {
  out_ << std::fixed << std::setprecision(6) << t << "," << left << "," << right << "\n";
  Check(out_, file_.Path());
}

void EncodersCsvWriter::Sample(double t, uint64_t traction, int64_t steering) {
  out_ << std::fixed << std::setprecision(6) << t << "," << traction << "," << steering << "\n";
  Check(out_, file_.Path());
}

void EncodersCsvWriter::Close() {
  file_.Commit();
}

FixesCsvWriter::FixesCsvWriter(const std::string& path, bool with_variances,
                               const std::vector<std::string>& inputs)
    : file_(path, inputs), out_(file_.Stream()), with_variances_(with_variances) {
  out_ << std::setprecision(9);
  out_ << "t,x,y,theta" << (with_variances ? ",var_x,var_y,var_theta" : "") << "\n";
}

void FixesCsvWriter::Fix(double t, const geometry::Pose2D& p, double vx, double vy, double vt) {
  out_ << std::fixed << std::setprecision(6) << t << "," << p.x << "," << p.y << ","
       << std::setprecision(9) << p.theta;
  if (with_variances_) out_ << std::scientific << "," << vx << "," << vy << "," << vt;
  out_ << "\n";
  Check(out_, file_.Path());
}

void FixesCsvWriter::Close() {
  file_.Commit();
}

}  // namespace structloc::log_formats
