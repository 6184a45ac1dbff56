// The saved pose written off the component's main loop (see header).
#include "structloc/localisation/pose_saver.hpp"

#include <exception>
#include <iostream>

namespace structloc::localisation {

PoseSaver::PoseSaver(std::string path) : path_(std::move(path)), thread_([this] { Loop(); }) {}

PoseSaver::~PoseSaver() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_one();
  thread_.join();
}

void PoseSaver::Save(const SavedPose& pose) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    pending_ = pose;
  }
  wake_.notify_one();
}

void PoseSaver::Loop() {
  std::unique_lock<std::mutex> lock(mutex_);
  while (true) {
    wake_.wait(lock, [this] { return pending_.has_value() || stopping_; });
    if (!pending_) return;  // stopping, nothing left to write
    const SavedPose pose = *pending_;
    pending_.reset();
    lock.unlock();
    try {
      SavePoseAtomically(path_, pose);
    } catch (const std::exception& e) {
      std::cerr << "localisation: " << e.what() << std::endl;
    }
    lock.lock();
  }
}

}  // namespace structloc::localisation
