// libFuzzer target: the localisation parameter file (<localisation_params>:
// the pipeline's blocks and the tracking session's <tracking> block).
#include "fuzz_input.hpp"
#include "structloc/localisation_core/localiser/localiser_options.hpp"
#include "structloc/localisation_core/tracking/tracking_session_options.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = structloc::fuzz::WriteInput(data, size, "params.xml");
  structloc::fuzz::Parse([&] { (void)structloc::localisation_core::LoadLocaliserOptions(path); });
  structloc::fuzz::Parse([&] { (void)structloc::localisation_core::LoadSessionOptions(path); });
  return 0;
}
