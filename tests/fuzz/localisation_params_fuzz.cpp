// libFuzzer target: the localisation parameter file (<localisation_params>:
// the pipeline's blocks and the tracking session's <tracking> block).
#include <stdexcept>

#include "fuzz_input.hpp"
#include "structloc/localisation_core/localiser_options.hpp"
#include "structloc/localisation_core/tracking_session_options.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = structloc::fuzz::WriteInput(data, size, "params.xml");
  try {
    (void)structloc::localisation_core::LoadLocaliserOptions(path);
  } catch (const std::exception&) {
  }
  try {
    (void)structloc::localisation_core::LoadSessionOptions(path);
  } catch (const std::exception&) {
  }
  return 0;
}
