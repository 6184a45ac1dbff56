// Helpers for tests that use real DDS participants: the shipped QoS file
// (loopback-only default profile), polling with a deadline, and a one-sample
// round trip through a real DataWriter/DataReader pair.
#pragma once

#include <chrono>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "structloc/dds_common/node.hpp"
#include "test_paths.hpp"
#include "wait_until.hpp"

namespace structloc::testing {

inline std::string ShippedQos() {
  return SourcePath("qos/structloc_qos.xml");
}

inline dds_common::NodeOptions TestNodeOptions(const std::string& name, int domain) {
  dds_common::NodeOptions options;
  options.name = name;
  options.domain_id = domain;
  options.qos_file = ShippedQos();
  return options;
}

// Publishes `sample` on `topic` from `writer_node` until `reader_node`
// receives one, and returns what arrived (nullopt on timeout).
template <class PubSubType>
std::optional<typename PubSubType::type> RoundTrip(dds_common::Node& writer_node,
                                                   dds_common::Node& reader_node,
                                                   const dds_common::TopicSpec& topic,
                                                   typename PubSubType::type sample) {
  std::mutex mutex;
  std::optional<typename PubSubType::type> received;
  const auto subscription =
      reader_node.Subscribe<PubSubType>(topic, [&](const typename PubSubType::type& msg) {
        std::lock_guard<std::mutex> lock(mutex);
        received = msg;
      });
  auto writer = writer_node.CreateWriter<PubSubType>(topic);
  if (!WaitUntil([&] { return writer.MatchedReaders() > 0; }, std::chrono::seconds(10))) {
    return std::nullopt;
  }
  auto has = [&] {
    std::lock_guard<std::mutex> lock(mutex);
    return received.has_value();
  };
  for (int attempt = 0; attempt < 50 && !has(); ++attempt) {
    writer.Write(sample);
    WaitUntil(has, std::chrono::milliseconds(100));
  }
  std::lock_guard<std::mutex> lock(mutex);
  return received;
}

}  // namespace structloc::testing
