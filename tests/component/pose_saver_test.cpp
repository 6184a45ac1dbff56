// The localisation's saved pose is written off its main loop (PoseSaver): a
// Save returns while the write is held up (here by a FIFO nobody reads yet,
// as a disk busy for seconds would hold up an fsync), the newest pose is the
// one written, and what is pending when the saver stops is written, not lost.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <chrono>
#include <fstream>
#include <string>
#include <thread>

#include "structloc/localisation/pose_saver.hpp"
#include "temp_dir.hpp"

namespace structloc {
namespace {

using namespace std::chrono_literals;

localisation::SavedPose PoseAt(double x) {
  localisation::SavedPose pose;
  pose.map_to_odom = {x, 2.0, 0.5};
  return pose;
}

TEST(PoseSaver, TheNewestPoseIsWrittenAndNothingPendingIsLostOnStop) {
  testing::TempDir dir;
  const std::string path = dir / "pose_state";
  {
    localisation::PoseSaver saver(path);
    for (int i = 1; i <= 200; ++i) saver.Save(PoseAt(i));
  }
  const auto saved = localisation::LoadSavedPose(path);
  ASSERT_TRUE(saved.has_value());
  EXPECT_EQ(saved->map_to_odom.x, 200.0);
  EXPECT_EQ(saved->map_to_odom.y, 2.0);
}

TEST(PoseSaver, SaveReturnsWhileTheWriteIsHeldUp) {
  testing::TempDir dir;
  const std::string path = dir / "pose_fifo";
  ASSERT_EQ(::mkfifo(path.c_str(), 0600), 0);
  localisation::PoseSaver saver(path);
  const auto started = std::chrono::steady_clock::now();
  saver.Save(PoseAt(7.0));  // the writer now waits for a reader of the FIFO
  EXPECT_LT(std::chrono::steady_clock::now() - started, 1s);
  std::this_thread::sleep_for(200ms);
  // Reading lets the held-up write through.
  std::string line;
  std::ifstream in(path);
  std::getline(in, line);
  EXPECT_EQ(line.rfind("map_to_odom 7 ", 0), 0u) << line;
}

}  // namespace
}  // namespace structloc
