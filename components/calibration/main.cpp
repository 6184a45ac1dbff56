// structloc_calibration: entry point of the odometry-calibration component.
#include "calibration_component.hpp"

int main(int argc, char** argv) {
  return structloc::dds::RunComponent(
      argc, argv, "calibration", {},
      [](structloc::dds::Node& node, const structloc::config::CommandLine&) {
        return std::make_unique<structloc::calibration::CalibrationComponent>(node);
      });
}
