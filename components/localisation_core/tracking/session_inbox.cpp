// Session inbox (see header).
#include "structloc/localisation_core/tracking/session_inbox.hpp"

namespace structloc::localisation_core {

void SessionInputs::Clear() {
  scan.reset();
  scan_arrived_s = 0.0;
  dropped = 0;
  odometry.clear();
  initial_poses.clear();
}

void SessionInbox::OfferScan(SessionScan scan, double now) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (inputs_.scan) ++inputs_.dropped;  // overload: the newest scan wins
    inputs_.scan = std::move(scan);
    inputs_.scan_arrived_s = now;
    last_scan_s_ = now;
    new_input_ = true;
  }
  wake_.notify_one();
}

void SessionInbox::OfferOdometry(double stamp, const geometry::Pose2D& pose, double now) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    last_odometry_s_ = now;
    if (inputs_.odometry.size() >= kMaxQueuedOdometry) {
      ++odometry_overflow_;
      return;
    }
    inputs_.odometry.push_back({stamp, pose});
    new_input_ = true;
  }
  wake_.notify_one();  // a waiting scan may now be covered
}

void SessionInbox::OfferInitialPose(const InitialPoseInput& pose) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    inputs_.initial_poses.push_back(pose);
    new_input_ = true;
  }
  wake_.notify_one();
}

bool SessionInbox::WaitAndTake(std::chrono::milliseconds timeout, SessionInputs& inputs) {
  inputs.Clear();
  std::unique_lock<std::mutex> lock(mutex_);
  // The flag keeps a notification sent while the taker was busy.
  wake_.wait_for(lock, timeout, [this] { return stopping_ || new_input_; });
  if (stopping_) return false;
  new_input_ = false;
  std::swap(inputs, inputs_);
  return true;
}

void SessionInbox::Stop() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
}

double SessionInbox::LastScanArrival() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return last_scan_s_;
}

double SessionInbox::LastOdometryArrival() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return last_odometry_s_;
}

uint64_t SessionInbox::OdometryOverflow() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return odometry_overflow_;
}

}  // namespace structloc::localisation_core
