// structloc_calibration: entry point of the odometry-calibration component.
#include "structloc/calibration/calibration_component.hpp"
#include "structloc/kinematics/robot_parameters.hpp"

int main(int argc, char** argv) {
  namespace cal = structloc::calibration;
  return structloc::dds_common::RunComponent(
      argc, argv, "calibration",
      {{"robot", true,
        "nominal robot parameters (default: maps/robots/tricycle.xml in structloc's data folder)"},
       {"record-s", true,
        "recording length in seconds of stamp time, 0 = until stopped (default 60)"},
       {"fix-topic", true,
        "PoseWithCovarianceStamped topic with the fixes (default rt/pose; not empty, not another "
        "structloc topic)"},
       {"estimate", true,
        "comma-separated parameters (default wheel_radius,axle_distance,steering_offset; "
        "differential drive: left_wheel_radius,right_wheel_radius,wheel_separation)"},
       {"window-s", true,
        "online: re-estimate over the last this many seconds of stamp time, again and again "
        "(0 = one recording of --record-s, the default)"},
       {"every-s", true, "online: a new estimate every this many seconds (default 30)"},
       {"out-dir", true,
        "write encoders.csv, fixes.csv and calibrated.xml here (created at start-up; must be a "
        "writable folder)"},
       {"exit-when-done", false,
        "exit after publishing the result (exit code 1 when the calibration failed or could not "
        "be written)"}},
      [](structloc::dds_common::Node& node, const structloc::config::CommandLine& cli,
         const structloc::dds_common::StopWait&) {
        cal::CalibrationComponentOptions o;
        o.robot_path = cli.PathOr("robot", "maps/robots/tricycle.xml");
        o.nominal = structloc::kinematics::LoadRobotParameters(o.robot_path);
        o.record_s = cli.Number("record-s", o.record_s);
        o.fix_topic = cli.GetOr("fix-topic", o.fix_topic);
        if (auto dir = cli.Get("out-dir")) {
          if (dir->empty()) throw structloc::config::ConfigError("--out-dir is empty");
          o.out_dir = *dir;
        }
        o.exit_when_done = cli.Has("exit-when-done");
        o.online_options.window_s = cli.Number("window-s", 0.0);
        o.online = o.online_options.window_s > 0;
        o.online_options.period_s = cli.Number("every-s", o.online_options.period_s);
        if (!(o.online_options.window_s >= 0)) {
          throw structloc::config::ConfigError("--window-s must be >= 0 (0 = no online mode)");
        }
        o.calibration.estimate = structloc::calibration_core::DefaultEstimate(o.nominal.kind);
        if (auto list = cli.Get("estimate")) {
          o.calibration.estimate = structloc::calibration_core::ParseParameterList(*list);
        }
        o.Validate();
        return std::make_unique<cal::CalibrationComponent>(node, o);
      },
      structloc::kinematics::PrintRobotParameters);
}
