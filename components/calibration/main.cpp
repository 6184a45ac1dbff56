// structloc_calibration: entry point of the odometry-calibration component.
#include <sstream>

#include "calibration_component.hpp"

#ifndef STRUCTLOC_SHARE_DIR
#error "STRUCTLOC_SHARE_DIR must be defined by the build"
#endif

int main(int argc, char** argv) {
  using structloc::config::ConfigError;
  namespace cal = structloc::calibration;
  return structloc::dds::RunComponent(
      argc, argv, "calibration",
      {{"robot", true,
        "nominal robot parameters (default " STRUCTLOC_SHARE_DIR "/maps/robots/tricycle.xml)"},
       {"record-s", true,
        "recording length in seconds of stamp time, 0 = until stopped (default 60)"},
       {"fix-topic", true, "PoseWithCovarianceStamped topic with the fixes (default rt/pose)"},
       {"estimate", true,
        "comma-separated parameters (default wheel_radius,axle_distance,steering_offset)"},
       {"out-dir", true, "write encoders.csv, fixes.csv and calibrated.xml here"},
       {"exit-when-done", false, "exit after publishing the result"}},
      [](structloc::dds::Node& node, const structloc::config::CommandLine& cli) {
        cal::CalibrationComponentOptions o;
        o.nominal = structloc::kinematics::LoadRobotParameters(
            cli.GetOr("robot", STRUCTLOC_SHARE_DIR "/maps/robots/tricycle.xml"));
        o.record_s = cli.Number("record-s", o.record_s);
        if (o.record_s < 0) throw ConfigError("--record-s must be >= 0");
        o.fix_topic = cli.GetOr("fix-topic", o.fix_topic);
        o.out_dir = cli.GetOr("out-dir", "");
        o.exit_when_done = cli.Has("exit-when-done");
        if (auto list = cli.Get("estimate")) {
          o.calibration.estimate.fill(false);
          std::stringstream ss(*list);
          for (std::string name; std::getline(ss, name, ',');) {
            bool known = false;
            for (int k = 0; k < cal::kParameterCount; ++k) {
              if (name == cal::ParameterName(static_cast<cal::Parameter>(k))) {
                o.calibration.estimate[static_cast<size_t>(k)] = known = true;
              }
            }
            if (!known) throw ConfigError("--estimate: unknown parameter '" + name + "'");
          }
        }
        return std::make_unique<cal::CalibrationComponent>(node, o);
      });
}
