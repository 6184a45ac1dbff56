// structloc_check_qos FILE [FILE...]: validates QoS profiles files with the
// exact code the components use (QosProfiles::Load: values, leases and the
// topic profiles) and lists their profiles; exit 2 when any file is broken.
#include <iostream>

#include "structloc/dds_common/qos_profiles.hpp"

int main(int argc, char** argv) {
  if (argc < 2 || std::string(argv[1]) == "--help") {
    (argc < 2 ? std::cerr : std::cout)
        << "usage: structloc_check_qos QOS_FILE.xml [QOS_FILE.xml ...]" << std::endl;
    return argc < 2 ? 2 : 0;
  }
  int result = 0;
  for (int i = 1; i < argc; ++i) {
    try {
      const auto qos = structloc::dds_common::QosProfiles::Load(argv[i]);
      for (const auto& p : qos.ParticipantProfiles()) {
        const auto pq = qos.Participant(p);
        std::cout << "participant " << p << " lease "
                  << pq.wire_protocol().builtin.discovery_config.leaseDuration.seconds << " s\n";
      }
      for (const auto& p : qos.WriterProfiles()) std::cout << "data_writer " << p << "\n";
      for (const auto& p : qos.ReaderProfiles()) std::cout << "data_reader " << p << "\n";
      std::cout << argv[i] << ": OK" << std::endl;
    } catch (const std::exception& e) {
      std::cerr << e.what() << std::endl;
      result = 2;
    }
  }
  return result;
}
