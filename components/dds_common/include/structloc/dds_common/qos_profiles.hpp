// Loads a Fast DDS QoS profiles file and hands out QoS by profile name, after
// validating what Fast DDS 2.9 would silently accept (depth 0, negative
// durations, unknown kinds, a lease of 0) or replace with defaults (a broken
// file), and that every topic profile of the topic table exists for both
// writers and readers, and that no profile sets a DDS Security property
// (dds.sec.*: security comes from --security-keystore alone, and a profile's
// property would take precedence over the enclave's). structloc_check_qos runs
// exactly this.
#pragma once

#include <fastdds/dds/domain/qos/DomainParticipantQos.hpp>
#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/publisher/qos/DataWriterQos.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/subscriber/qos/DataReaderQos.hpp>

#include <mutex>
#include <set>
#include <stdexcept>
#include <string>

namespace structloc::dds_common {

// A QoS problem: the message names the file (and line where known).
class QosError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// True for a DDS Security property name (dds.sec.*, in any case, blanks
// around it ignored).
bool IsSecurityProperty(const std::string& name);

// Fast DDS 2.9 keeps its XML profiles in process-wide tables it does not
// lock, and creating a participant loads its default profiles into them
// (upstream fixed that after 2.9): loading, reading and creating a
// participant from several threads at once (nodes made side by side in one
// process) can corrupt them and abort the process. Every such call holds
// this lock.
std::mutex& FastDdsProfileTables();

class QosProfiles {
 public:
  // Validates the file's structure, values and topic profiles, then loads it
  // into Fast DDS. Throws QosError naming the file, line and problem.
  static QosProfiles Load(const std::string& path);
  // The same validation without loading the file into Fast DDS (what Load
  // checks first; fuzzed on its own).
  static QosProfiles Check(const std::string& path);

  eprosima::fastdds::dds::DomainParticipantQos Participant(const std::string& profile) const;
  eprosima::fastdds::dds::DataWriterQos Writer(eprosima::fastdds::dds::Publisher& publisher,
                                               const std::string& profile) const;
  eprosima::fastdds::dds::DataReaderQos Reader(eprosima::fastdds::dds::Subscriber& subscriber,
                                               const std::string& profile) const;

  const std::string& Path() const { return path_; }
  const std::set<std::string>& ParticipantProfiles() const { return participant_profiles_; }
  const std::set<std::string>& WriterProfiles() const { return writer_profiles_; }
  const std::set<std::string>& ReaderProfiles() const { return reader_profiles_; }

 private:
  std::string path_;
  std::set<std::string> participant_profiles_;
  std::set<std::string> writer_profiles_;
  std::set<std::string> reader_profiles_;
};

}  // namespace structloc::dds_common
