// libFuzzer target: robot parameter files (tricycle or differential drive).
#include <stdexcept>

#include "fuzz_input.hpp"
#include "structloc/kinematics/robot_parameters.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = structloc::fuzz::WriteInput(data, size, "robot.xml");
  try {
    (void)structloc::kinematics::LoadRobotParameters(path);
  } catch (const std::exception&) {
  }
  return 0;
}
