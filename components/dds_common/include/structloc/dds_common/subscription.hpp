// A subscription as an RAII handle owned by the subscriber: the DataReader and
// the listener that calls back into the subscriber live exactly as long as the
// handle. Destroying it (or Reset()) waits for a callback that is running,
// makes sure none starts afterwards and deletes the reader, so an object that
// holds its subscriptions as members can never be called back once it is
// being destroyed. A subscription that outlives its Node only lets go of its
// listener: the Node already deleted the reader with its participant.
#pragma once

#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/DataReaderListener.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>

#include <atomic>
#include <functional>
#include <iostream>
#include <memory>
#include <mutex>
#include <string>

#include "structloc/dds_common/peer_monitor.hpp"

namespace structloc::dds_common {

// A reader listener whose callback can be cut off for good.
class DetachableListener : public eprosima::fastdds::dds::DataReaderListener {
 public:
  // After this returns the callback is not running and never runs again.
  virtual void Detach() = 0;
  // Takes the samples that arrived while callbacks were held (see Node).
  virtual void TakeWaiting() = 0;
};

class Subscription {
 public:
  Subscription() = default;
  // `node_alive` expires when the Node that made the reader is destroyed.
  Subscription(eprosima::fastdds::dds::Subscriber* subscriber,
               eprosima::fastdds::dds::DataReader* reader,
               std::shared_ptr<DetachableListener> listener, std::weak_ptr<const bool> node_alive)
      : subscriber_(subscriber),
        reader_(reader),
        listener_(std::move(listener)),
        node_alive_(std::move(node_alive)) {}
  ~Subscription() { Reset(); }
  Subscription(Subscription&& other) noexcept { *this = std::move(other); }
  Subscription& operator=(Subscription&& other) noexcept {
    if (this != &other) {
      Reset();
      subscriber_ = other.subscriber_;
      reader_ = other.reader_;
      listener_ = std::move(other.listener_);
      node_alive_ = std::move(other.node_alive_);
      other.subscriber_ = nullptr;
      other.reader_ = nullptr;
    }
    return *this;
  }
  Subscription(const Subscription&) = delete;
  Subscription& operator=(const Subscription&) = delete;

  // Stops the callbacks (waiting for one in flight) and deletes the reader.
  void Reset() {
    if (listener_) listener_->Detach();
    if (reader_ != nullptr && !node_alive_.expired()) {
      reader_->set_listener(nullptr);
      subscriber_->delete_datareader(reader_);
    }
    listener_.reset();
    reader_ = nullptr;
    subscriber_ = nullptr;
  }
  bool Active() const { return reader_ != nullptr; }
  // Writers matched to this reader now (0 once Reset).
  size_t MatchedWriters() const {
    if (reader_ == nullptr || node_alive_.expired()) return 0;
    eprosima::fastdds::dds::SubscriptionMatchedStatus status;
    reader_->get_subscription_matched_status(status);
    return static_cast<size_t>(status.current_count);
  }

 private:
  eprosima::fastdds::dds::Subscriber* subscriber_ = nullptr;
  eprosima::fastdds::dds::DataReader* reader_ = nullptr;
  std::shared_ptr<DetachableListener> listener_;
  std::weak_ptr<const bool> node_alive_;
};

// Calls `callback` on a DDS thread for every valid sample of a PubSubType
// topic; exceptions it throws are caught and logged so one bad sample cannot
// stop the component. While `held` is set, samples wait in the reader until
// TakeWaiting().
template <class PubSubType>
class CallbackListener : public DetachableListener {
 public:
  CallbackListener(std::string node, std::string topic, PeerMonitor& monitor,
                   const std::atomic<bool>& held,
                   std::function<void(const typename PubSubType::type&)> callback)
      : node_(std::move(node)),
        topic_(std::move(topic)),
        monitor_(monitor),
        held_(held),
        callback_(std::move(callback)) {}
  void on_requested_incompatible_qos(
      eprosima::fastdds::dds::DataReader*,
      const eprosima::fastdds::dds::RequestedIncompatibleQosStatus& status) override {
    monitor_.IncompatibleQos(topic_, "subscription", status.last_policy_id);
  }
  void Detach() override {
    std::lock_guard<std::mutex> lock(mutex_);  // waits for a running callback
    callback_ = nullptr;
  }
  // The reader this listener serves, for TakeWaiting().
  void Attach(eprosima::fastdds::dds::DataReader* reader) { reader_ = reader; }
  void TakeWaiting() override {
    if (reader_ != nullptr) Drain(reader_);
  }
  void on_data_available(eprosima::fastdds::dds::DataReader* reader) override {
    if (held_) return;  // taken by TakeWaiting() when the hold ends
    Drain(reader);
  }

 private:
  // Takes every waiting sample and calls back, on whichever thread comes
  // first, and never waits for a thread that is taking: Fast DDS calls
  // on_data_available with the reader locked, and taking locks the reader, so
  // a DDS thread waiting here for TakeWaiting's thread would hold the lock
  // that thread needs (a deadlock that once hung a component at start-up). A
  // thread that finds another taking leaves the samples to it: `pending_`
  // makes the taker look again once it has let go.
  void Drain(eprosima::fastdds::dds::DataReader* reader) {
    pending_ = true;
    while (pending_) {
      std::unique_lock<std::mutex> lock(mutex_, std::try_to_lock);
      if (!lock.owns_lock()) return;
      pending_ = false;
      typename PubSubType::type sample;
      eprosima::fastdds::dds::SampleInfo info;
      while (callback_ && reader->take_next_sample(&sample, &info) ==
                              eprosima::fastrtps::types::ReturnCode_t::RETCODE_OK) {
        if (!info.valid_data) continue;
        try {
          callback_(sample);
        } catch (const std::exception& e) {
          std::cerr << node_ << ": error handling a sample on " << topic_ << ": " << e.what()
                    << std::endl;
        }
      }
    }
  }

  std::string node_;
  std::string topic_;
  PeerMonitor& monitor_;
  const std::atomic<bool>& held_;
  eprosima::fastdds::dds::DataReader* reader_ = nullptr;
  std::mutex mutex_;  // held while taking and calling back
  std::atomic<bool> pending_{false};
  std::function<void(const typename PubSubType::type&)> callback_;
};

}  // namespace structloc::dds_common
