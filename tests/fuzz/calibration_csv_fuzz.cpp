// libFuzzer target: the calibration's encoders.csv (both drive kinds, a
// 16-bit and a 64-bit counter) and fixes.csv.
#include "fuzz_input.hpp"
#include "structloc/calibration_core/calibration_data.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  namespace cc = structloc::calibration_core;
  const std::string path = structloc::fuzz::WriteInput(data, size, "input.csv");
  for (const auto kind : {structloc::kinematics::DriveKind::kTricycle,
                          structloc::kinematics::DriveKind::kDifferential}) {
    for (const int bits : {16, 64}) {
      structloc::fuzz::Parse([&] { (void)cc::ReadEncodersCsv(path, bits, kind); });
    }
  }
  structloc::fuzz::Parse([&] { (void)cc::ReadFixesCsv(path); });
  return 0;
}
