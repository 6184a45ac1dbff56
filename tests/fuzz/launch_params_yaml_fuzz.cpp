// libFuzzer target: ROS 2 parameter files (`<param from="params.yaml"/>`).
#include "fuzz_input.hpp"
#include "structloc/process/launch_param_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = structloc::fuzz::WriteInput(data, size, "params.yaml");
  structloc::fuzz::Parse(
      [&] { (void)structloc::process::ReadNodeParameters(path, "robot1/localisation"); });
  return 0;
}
