// Offline recorder (see header).
#include "structloc/simulation_core/recorder.hpp"

#include <filesystem>
#include <iomanip>

#include "structloc/config/output_file.hpp"
#include "structloc/log_formats/recording_writers.hpp"
#include "structloc/simulation_core/simulation.hpp"

namespace structloc::simulation_core {

RecordingSummary RecordScenario(const Scenario& scenario, const std::string& out_dir) {
  std::filesystem::create_directories(out_dir);
  log_formats::CarmenWriter clf(out_dir + "/run.clf");
  log_formats::TumWriter truth(out_dir + "/truth.tum");
  const bool differential = scenario.nominal.kind == kinematics::DriveKind::kDifferential;
  log_formats::EncodersCsvWriter encoders(out_dir + "/encoders.csv", {}, differential);
  const auto sample = [&](const SimState& s) {
    if (differential) {
      encoders.SampleWheels(s.time, s.left_ticks, s.right_ticks);
    } else {
      encoders.Sample(s.time, s.traction_ticks, s.steering_ticks);
    }
  };
  config::OutputFile initial(out_dir + "/initial_pose");
  clf.Comment("scenario " + scenario.name + ", seed " + std::to_string(scenario.seed));
  Simulation sim(scenario);
  // ROBOTLASER1 lines carry no beam timing: this PARAM lets our replay de-skew.
  clf.Param("structloc_laser_time_increment", sim.LaserTimeIncrement());
  RecordingSummary summary;
  const int odom_every =
      std::max(1, static_cast<int>(std::lround(1.0 / (scenario.odom_rate_hz * scenario.step_s))));
  // The state at t = 0, so that the first scan (stamped 0) has odometry at its time.
  clf.Odometry(0.0, sim.State().odometry, 0.0, 0.0);
  sample(sim.State());
  bool first_scan = true;
  for (long step = 1; !sim.Finished(); ++step) {
    const SimState& s = sim.Step();
    if (step % odom_every == 0) {
      clf.Odometry(s.time, s.odometry, s.odom_linear, s.odom_angular);
      sample(s);
      ++summary.odometry_lines;
    }
    if (auto scan = sim.TakeScan()) {
      log_formats::CarmenLaser laser;
      laser.start_angle = scan->angle_min;
      laser.angular_resolution = scan->angle_increment;
      laser.field_of_view = scan->angle_increment * static_cast<double>(scan->ranges.size() - 1);
      laser.max_range = scan->range_max;
      const geometry::Pose2D laser_pose = geometry::Compose(scan->odometry, scenario.laser.mount);
      clf.RobotLaser(scan->stamp, laser, scan->ranges, laser_pose, scan->odometry, s.odom_linear,
                     s.odom_angular);
      truth.Pose(scan->stamp, scan->truth);
      if (first_scan) {
        initial.Stream() << std::setprecision(9) << scan->truth.x << " " << scan->truth.y << " "
                         << scan->truth.theta << "\n";
        first_scan = false;
      }
      ++summary.scans;
    }
  }
  // All four reach the disk before any replaces an earlier recording.
  clf.Flush();
  truth.Flush();
  encoders.Flush();
  initial.Flush();
  clf.Close();
  truth.Close();
  encoders.Close();
  initial.Commit();
  const auto& s = sim.State();
  summary.duration_s = s.time;
  // The odometry frame starts at the initial pose: compare in the map frame.
  const geometry::Pose2D odom_in_map = geometry::Compose(scenario.initial_pose, s.odometry);
  summary.odometry_final_error_m = (odom_in_map.Translation() - s.truth.Translation()).norm();
  return summary;
}

}  // namespace structloc::simulation_core
