// libFuzzer target: `structloc map build --params` files (<map_build_params>).
#include "fuzz_input.hpp"
#include "structloc/map_building/map_builder.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = structloc::fuzz::WriteInput(data, size, "map_build.xml");
  structloc::fuzz::Parse([&] { (void)structloc::map_building::LoadMapBuildOptions(path); });
  return 0;
}
