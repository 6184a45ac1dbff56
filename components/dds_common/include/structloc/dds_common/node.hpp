// A DDS participant with one publisher and one subscriber, the way a ROS 2
// node looks on the wire: typed writers and callback readers created from the
// topic table and QoS profiles by name; subscriptions are handles owned by
// the subscriber (subscription.hpp). Components are thin adapters on top.
#pragma once

#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/publisher/DataWriterListener.hpp>
#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/topic/Topic.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>

#include <atomic>
#include <functional>
#include <iostream>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "structloc/dds_common/peer_monitor.hpp"
#include "structloc/dds_common/qos_profiles.hpp"
#include "structloc/dds_common/security_enclave.hpp"
#include "structloc/dds_common/subscription.hpp"
#include "structloc/dds_common/topic_namespace.hpp"
#include "structloc/dds_common/topics.hpp"

namespace structloc::dds_common {

struct NodeOptions {
  std::string name;      // shown in reports and diagnostics
  int domain_id = 0;     // DDS domain, 0..232 (0..101 on Linux, see domain_ports.hpp)
  std::string qos_file;  // Fast DDS profiles XML
  std::string participant_profile = "structloc_localhost";
  // ROS 2 namespace of every topic this node reads or writes ("" = none;
  // normalised, see topic_namespace.hpp): rt/scan becomes rt/<ns>/scan.
  std::string ros_namespace;
  // DDS Security (off by default): the keystore and this node's identity in it.
  SecurityOptions security;
};

// A typed DataWriter handle; Write returns false when DDS refused the sample.
template <class PubSubType>
class TopicWriter {
 public:
  using Message = typename PubSubType::type;
  TopicWriter() = default;
  explicit TopicWriter(eprosima::fastdds::dds::DataWriter* writer) : writer_(writer) {}
  // Fast DDS takes a non-const pointer but only serialises the sample.
  bool Write(const Message& message) {
    return writer_ != nullptr && writer_->write(const_cast<Message*>(&message));
  }
  size_t MatchedReaders() const {
    eprosima::fastdds::dds::PublicationMatchedStatus status;
    writer_->get_publication_matched_status(status);
    return static_cast<size_t>(status.current_count);
  }
  eprosima::fastdds::dds::DataWriter* Raw() const { return writer_; }

 private:
  eprosima::fastdds::dds::DataWriter* writer_ = nullptr;
};

class Node {
 public:
  // Throws QosError or std::runtime_error naming what is wrong.
  explicit Node(const NodeOptions& options);
  ~Node();
  Node(const Node&) = delete;
  Node& operator=(const Node&) = delete;

  template <class PubSubType>
  TopicWriter<PubSubType> CreateWriter(const TopicSpec& unqualified) {
    const TopicSpec topic = InNamespace(unqualified, options_.ros_namespace);
    auto* dds_topic = TopicFor<PubSubType>(topic.name);
    auto listener = std::make_unique<WriterListener>(*monitor_, topic.name);
    auto* writer = publisher_->create_datawriter(
        dds_topic, qos_.Writer(*publisher_, topic.qos_profile), listener.get());
    if (writer == nullptr) throw std::runtime_error("cannot create writer for " + topic.name);
    writer_listeners_.push_back(std::move(listener));
    endpoints_.push_back("publishes  " + Describe(topic, dds_topic->get_type_name()));
    return TopicWriter<PubSubType>(writer);
  }

  // `callback` runs on a DDS thread for every valid sample, as long as the
  // returned handle lives: keep it as a member of the object the callback
  // points into, declared after everything the callback uses, so that it is
  // destroyed first. Exceptions the callback throws are caught and logged.
  template <class PubSubType>
  [[nodiscard]] Subscription Subscribe(
      const TopicSpec& unqualified,
      std::function<void(const typename PubSubType::type&)> callback) {
    const TopicSpec topic = InNamespace(unqualified, options_.ros_namespace);
    auto* dds_topic = TopicFor<PubSubType>(topic.name);
    auto listener = std::make_shared<CallbackListener<PubSubType>>(
        options_.name, topic.name, *monitor_, callbacks_held_, std::move(callback));
    auto* reader = subscriber_->create_datareader(
        dds_topic, qos_.Reader(*subscriber_, topic.qos_profile), listener.get());
    if (reader == nullptr) throw std::runtime_error("cannot create reader for " + topic.name);
    listener->Attach(reader);
    endpoints_.push_back("subscribes " + Describe(topic, dds_topic->get_type_name()));
    listeners_.push_back(listener);
    return Subscription(subscriber_, reader, std::move(listener), alive_);
  }

  // While held, arriving samples wait in their readers and no callback runs:
  // a component is built with callbacks held, so that none reaches an object
  // whose constructor has not finished. Releasing takes what arrived meanwhile
  // (a one-shot initial pose, a latched result), on the calling thread.
  void HoldCallbacks() { callbacks_held_ = true; }
  void ReleaseCallbacks();

  // One line per endpoint: direction, topic, DDS type name, QoS profile.
  std::string EndpointReport() const;
  const NodeOptions& Options() const { return options_; }
  // Problems with peers that hold now (incompatible QoS, a duplicate of this
  // node on the domain), one sentence each; empty when all is well.
  std::vector<std::string> PeerProblems() const { return monitor_->Problems(); }

 private:
  class WriterListener : public eprosima::fastdds::dds::DataWriterListener {
   public:
    WriterListener(PeerMonitor& monitor, std::string topic)
        : monitor_(monitor), topic_(std::move(topic)) {}
    void on_offered_incompatible_qos(
        eprosima::fastdds::dds::DataWriter*,
        const eprosima::fastdds::dds::OfferedIncompatibleQosStatus& status) override {
      monitor_.IncompatibleQos(topic_, "publication", status.last_policy_id);
    }

   private:
    PeerMonitor& monitor_;
    std::string topic_;
  };

  template <class PubSubType>
  eprosima::fastdds::dds::Topic* TopicFor(const std::string& name) {
    auto it = topics_.find(name);
    if (it != topics_.end()) return it->second;
    eprosima::fastdds::dds::TypeSupport type(new PubSubType());
    if (participant_->find_type(type.get_type_name()).empty()) type.register_type(participant_);
    auto* topic = participant_->create_topic(name, type.get_type_name(),
                                             eprosima::fastdds::dds::TOPIC_QOS_DEFAULT);
    if (topic == nullptr) throw std::runtime_error("cannot create topic " + name);
    topics_[name] = topic;
    return topic;
  }

  static std::string Describe(const TopicSpec& topic, const std::string& type_name);
  // Deletes the new participant and throws unless every enclave property is
  // the first of its name in the participant's QoS (the one Fast DDS uses).
  void RequireSecurityAsAsked(const std::vector<std::pair<std::string, std::string>>& security);

  NodeOptions options_;
  QosProfiles qos_;
  std::unique_ptr<PeerMonitor> monitor_;  // outlives the participant that calls it
  std::atomic<bool> callbacks_held_{false};
  // The listeners of live subscriptions, for ReleaseCallbacks().
  std::vector<std::weak_ptr<DetachableListener>> listeners_;
  // Expires with the Node, so that a subscription outliving it does not touch
  // the deleted reader.
  std::shared_ptr<const bool> alive_ = std::make_shared<const bool>(true);
  eprosima::fastdds::dds::DomainParticipant* participant_ = nullptr;
  eprosima::fastdds::dds::Publisher* publisher_ = nullptr;
  eprosima::fastdds::dds::Subscriber* subscriber_ = nullptr;
  std::map<std::string, eprosima::fastdds::dds::Topic*> topics_;
  std::vector<std::unique_ptr<WriterListener>> writer_listeners_;
  std::vector<std::string> endpoints_;
};

}  // namespace structloc::dds_common
