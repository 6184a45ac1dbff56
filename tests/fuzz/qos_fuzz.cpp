// libFuzzer target: structloc's own checks of a QoS profiles file (profile
// names, values, leases, the topic profiles the components need), which run
// before the file is handed to Fast DDS.
#include "fuzz_input.hpp"
#include "structloc/dds_common/qos_profiles.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = structloc::fuzz::WriteInput(data, size, "qos.xml");
  structloc::fuzz::Parse([&] { (void)structloc::dds_common::QosProfiles::Check(path); });
  return 0;
}
