// libFuzzer target: the calibration component's saved last result
// (last_result.cdr in --out-dir), read again at every start.
#include "fuzz_input.hpp"
#include "structloc/calibration/last_result_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = structloc::fuzz::WriteInput(data, size, "last_result.cdr");
  std::string why;
  (void)structloc::calibration::LoadLastResult(path, why);
  return 0;
}
