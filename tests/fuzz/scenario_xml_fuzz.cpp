// libFuzzer target: scenario XML (the simulator's and `structloc simulate`'s input).
#include "fuzz_input.hpp"
#include "structloc/simulation_core/scenario.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = structloc::fuzz::WriteInput(data, size, "scenario.xml");
  structloc::fuzz::Parse([&] { (void)structloc::simulation_core::LoadScenario(path); });
  return 0;
}
