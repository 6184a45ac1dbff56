// libFuzzer target: CARMEN logs as replay and the map makers read them (every
// record streamed), and as scans with poses for the map makers.
#include "fuzz_input.hpp"
#include "structloc/log_formats/carmen_reader.hpp"
#include "structloc/map_building/posed_scans.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = structloc::fuzz::WriteInput(data, size, "log.clf");
  structloc::fuzz::Parse([&] {
    structloc::log_formats::CarmenLimits limits;
    limits.max_beams = 2000;  // keeps one input's memory small; the limit itself is tested
    structloc::log_formats::CarmenReader reader(path, limits);
    structloc::log_formats::CarmenRecord record;
    while (reader.Next(record)) {
    }
  });
  structloc::fuzz::Parse([&] { (void)structloc::map_building::ReadPosedScans(path, {}); });
  return 0;
}
