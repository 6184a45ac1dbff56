// libFuzzer target: `structloc slam --slam-params` files (<slam_params>).
#include "fuzz_input.hpp"
#include "structloc/slam_core/slam.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = structloc::fuzz::WriteInput(data, size, "slam.xml");
  structloc::fuzz::Parse([&] { (void)structloc::slam_core::LoadSlamOptions(path); });
  return 0;
}
