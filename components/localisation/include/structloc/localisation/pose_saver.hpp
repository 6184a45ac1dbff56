// Writes the saved pose file (pose_state_file.hpp) on a thread of its own.
// Writing is atomic and so ends in an fsync, which a disk busy with other
// work can hold up for seconds; the component's main loop, which also
// publishes its diagnostics, only hands the newest pose over and goes on.
#pragma once

#include <condition_variable>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "structloc/localisation/pose_state_file.hpp"

namespace structloc::localisation {

class PoseSaver {
 public:
  explicit PoseSaver(std::string path);
  // Writes the pose still waiting, if any, then stops.
  ~PoseSaver();
  PoseSaver(const PoseSaver&) = delete;
  PoseSaver& operator=(const PoseSaver&) = delete;

  // Returns at once; a pose handed over before the previous one was written
  // replaces it (only the newest matters). A failed write is reported on
  // stderr, naming the file, and the next pose is tried again.
  void Save(const SavedPose& pose);

 private:
  void Loop();

  const std::string path_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::optional<SavedPose> pending_;
  bool stopping_ = false;
  std::thread thread_;  // last: started once the members above exist
};

}  // namespace structloc::localisation
