// libFuzzer target: robot parameter files (tricycle or differential drive).
#include "fuzz_input.hpp"
#include "structloc/kinematics/robot_parameters.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = structloc::fuzz::WriteInput(data, size, "robot.xml");
  structloc::fuzz::Parse([&] { (void)structloc::kinematics::LoadRobotParameters(path); });
  return 0;
}
