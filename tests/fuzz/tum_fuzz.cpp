// libFuzzer target: TUM trajectories (`--truth`).
#include "fuzz_input.hpp"
#include "structloc/log_formats/tum_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = structloc::fuzz::WriteInput(data, size, "truth.tum");
  structloc::fuzz::Parse([&] { (void)structloc::log_formats::ReadTum(path); });
  return 0;
}
