// structloc_check_qos FILE [PROFILE...]: validates a QoS profiles file with the
// exact code the components use and lists its profiles; exit 2 when broken.
#include <iostream>

#include <fastdds/dds/domain/DomainParticipantFactory.hpp>

#include "qos_profiles.hpp"

int main(int argc, char** argv) {
  if (argc < 2) {
    std::cerr << "usage: structloc_check_qos QOS_FILE.xml" << std::endl;
    return 2;
  }
  try {
    const auto qos = structloc::dds::QosProfiles::Load(argv[1]);
    for (const auto& p : qos.ParticipantProfiles()) {
      const auto pq = qos.Participant(p);
      std::cout << "participant " << p << " lease "
                << pq.wire_protocol().builtin.discovery_config.leaseDuration.seconds << " s\n";
    }
    for (const auto& p : qos.WriterProfiles()) std::cout << "data_writer " << p << "\n";
    for (const auto& p : qos.ReaderProfiles()) std::cout << "data_reader " << p << "\n";
    std::cout << argv[1] << ": OK" << std::endl;
    return 0;
  } catch (const std::exception& e) {
    std::cerr << e.what() << std::endl;
    return 2;
  }
}
